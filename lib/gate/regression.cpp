#include "gate/regression.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "base/number_text.h"

namespace crowdprof {

namespace {

std::vector<double> samples_of(const Result& result, const std::string& key) {
  const std::vector<double>* values = metric_samples(result, key);
  if (!values) throw std::invalid_argument("a result has no samples of " + key);
  return *values;
}

// The medians of each run of `result` for `key` when it pools `runs` or more
// runs (pooled_runs.h); empty otherwise.
std::vector<double> run_medians(const Result& result, const std::string& key, size_t runs) {
  if (!result.runs || result.runs->count < runs) return {};
  auto found = result.runs->median_ms.find(key);
  return found == result.runs->median_ms.end() ? std::vector<double>{} : found->second;
}

}  // namespace

std::string vertex_order_note(const std::string& baseline, const std::string& current) {
  auto order = [](const std::string& o) { return o == "file" ? "in the file's order" : "ordered by their joints"; };
  return std::string("the baseline hashed its vertices ") + order(baseline) + ", this run " + order(current) +
         " (record the baseline again to compare digests)";
}

std::string CheckResult::digest_note() const {
  if (baseline_digest == current_digest) return "same";
  if (digest_differs()) return "CHANGED";
  std::string why;
  if (arithmetic_differs()) {
    auto name = [](const std::string& simd, const char* which) { return simd.empty() ? std::string(which) : simd; };
    const std::string fused = baseline_fused ? name(baseline_simd, "the baseline") : name(current_simd, "this run");
    const std::string separate = baseline_fused ? name(current_simd, "this run") : name(baseline_simd, "the baseline");
    why = fused + " fused multiply-adds, " + separate + " did not (their last bits differ)";
  }
  if (order_differs())
    why += (why.empty() ? "" : "; ") + vertex_order_note(baseline_vertex_order, current_vertex_order);
  if (scheme_differs)
    why += std::string(why.empty() ? "" : "; ") +
           "one was recorded before a copy drawn whole under mesh LOD digested as without it (record it again)";
  return "not compared: " + why;
}

std::string CheckResult::digest_not_compared_why() const {
  std::vector<std::string> why;
  if (arithmetic_differs()) why.push_back("other arithmetic");
  if (order_differs()) why.push_back(why.empty() ? "other vertex order" : "vertex order");
  if (scheme_differs) why.push_back(why.empty() ? "other digest scheme" : "digest scheme");
  std::string text;
  for (size_t i = 0; i < why.size(); ++i) text += (i == 0 ? "" : i + 1 == why.size() ? " and " : ", ") + why[i];
  return text;
}

bool CheckResult::regressed() const {
  if (digest_differs() || !counters.empty() || !counters_missing.empty()) return true;
  return std::any_of(metrics.begin(), metrics.end(), [](const MetricCheck& m) { return m.regressed; });
}

void CheckResult::excuse_timings() {
  for (MetricCheck& m : metrics)
    if (m.regressed) {
      m.regressed = false;
      m.excused = true;
    }
}

namespace {

void decide(MetricCheck& m, const CheckOptions& options) {
  m.significant = m.p_adjusted < options.alpha && m.test.z > 0;
  m.regressed = m.tested && m.beyond_tolerance && m.beyond_floor && (m.significant || m.too_few_samples);
}

}  // namespace

MetricCheck check_metric(std::string metric, std::span<const double> baseline, std::span<const double> current,
                         const CheckOptions& options, double floor) {
  MetricCheck m;
  m.metric = std::move(metric);
  m.baseline = summarize(baseline);
  m.current = summarize(current);
  m.baseline_iqr = quantile(baseline, 0.75) - quantile(baseline, 0.25);
  m.current_iqr = quantile(current, 0.75) - quantile(current, 0.25);
  double grew = m.current.median - m.baseline.median;
  m.change = m.baseline.median > 0 ? grew / m.baseline.median : (grew > 0 ? INFINITY : 0.0);
  m.test = mann_whitney(current, baseline);
  m.p_adjusted = m.test.p;
  m.floor_ms = floor;
  m.beyond_tolerance = m.change > options.tolerance;
  m.beyond_floor = grew > floor;
  m.too_few_samples = std::min(baseline.size(), current.size()) < kMannWhitneyMinSamples;
  decide(m, options);
  return m;
}

void adjust_holm(std::vector<MetricCheck>& metrics, const CheckOptions& options) {
  std::vector<size_t> order(metrics.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return metrics[a].test.p < metrics[b].test.p; });
  double running = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    MetricCheck& m = metrics[order[k]];
    running = std::max(running, std::min(1.0, static_cast<double>(order.size() - k) * m.test.p));
    m.p_adjusted = running;
    decide(m, options);
  }
}

CheckResult check_results(const Result& baseline, const Result& current, const CheckOptions& options) {
  CheckResult result;
  // Runs are the unit when both results pool enough of them: processes differ
  // more than frames of one process do (gate/processes.h).
  std::vector<double> base_frame = run_medians(baseline, "frame_ms", kMannWhitneyMinSamples);
  double floor =
      floor_ms(options.floor, summarize(base_frame.empty() ? samples_of(baseline, "frame_ms") : base_frame).median);
  for (const std::string& key : options.metrics) {
    std::vector<double> a = run_medians(baseline, key, kMannWhitneyMinSamples);
    std::vector<double> b = run_medians(current, key, kMannWhitneyMinSamples);
    bool by_runs = !a.empty() && !b.empty();
    if (!by_runs) {
      a = samples_of(baseline, key);
      b = samples_of(current, key);
    }
    // The calibrated frame is a ratio: its floor is the same share of its own
    // median, or a floor in ms over the baseline's probe.
    double metric_floor = floor;
    if (key == "calibrated") {
      std::vector<double> base = run_medians(baseline, key, kMannWhitneyMinSamples);
      double median = summarize(base.empty() ? samples_of(baseline, key) : base).median;
      double probe = summarize(finite(baseline.samples.probe_ms)).median;
      metric_floor = options.floor.fraction_of_frame > 0 ? options.floor.fraction_of_frame * median
                                                         : (probe > 0 ? options.floor.ms / probe : 0);
    }
    result.metrics.push_back(check_metric(metric_display_name(key), a, b, options, metric_floor));
    result.metrics.back().unit = by_runs ? "runs" : "frames";
    if (key == "calibrated") result.metrics.back().value_unit = "probes";
  }
  adjust_holm(result.metrics, options);
  if (!options.compare_work) return result;
  const RecordedCounters& before = baseline.counters;
  const RecordedCounters& after = current.counters;
  for (size_t i = 0; i < kCounterFields.size(); ++i) {
    if (!before.present[i]) continue;
    std::string name(kCounterFields[i].name);
    if (!after.present[i]) {
      result.counters_missing.push_back(name);
      continue;
    }
    uint64_t b = before.values.*kCounterFields[i].member, a = after.values.*kCounterFields[i].member;
    if (a != b) result.counters.push_back({name, b, a});
  }
  result.baseline_digest = baseline.digest;
  result.current_digest = current.digest;
  result.baseline_simd = baseline.environment.simd;
  result.current_simd = current.environment.simd;
  result.baseline_fused = baseline.environment.fused_multiply_add;
  result.current_fused = current.environment.fused_multiply_add;
  result.digest_of_kernels = baseline.digest_cpu_vertices || current.digest_cpu_vertices;
  result.baseline_vertex_order = baseline.vertex_order;
  result.current_vertex_order = current.vertex_order;
  result.scheme_differs = baseline.digest_scheme != current.digest_scheme &&
                          (baseline.mesh_lod.has_value() || current.mesh_lod.has_value());
  return result;
}

// A small crowd's calibrated frame is a small share of the probe: significant
// digits, not decimals.
std::string metric_value_text(const MetricCheck& m, double v) {
  if (m.value_unit == "ms") return fixed(v, 3);
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

std::string format_check(const CheckResult& result, const CheckOptions& options) {
  std::ostringstream out;
  double whole = std::round(options.tolerance * 100.0);
  std::string tolerance =
      fixed(options.tolerance * 100.0, std::abs(options.tolerance * 100.0 - whole) < 1e-9 ? 0 : 1) + "%";
  bool corrected = result.metrics.size() > 1;
  auto metric_line = [&](const MetricCheck& m, const char* verdict) {
    const std::string unit = " " + m.value_unit;
    out << verdict << " " << m.metric << ": median " << metric_value_text(m, m.baseline.median) << unit << " -> "
        << metric_value_text(m, m.current.median) << unit << " (" << percent(m.change) << ", tolerance " << tolerance
        << ", floor " << metric_value_text(m, m.floor_ms) << unit << "), IQR " << metric_value_text(m, m.baseline_iqr)
        << " -> " << metric_value_text(m, m.current_iqr) << unit << ", p = " << p_value_text(m.test.p);
    if (corrected)
      out << " (Holm-corrected " << p_value_text(m.p_adjusted) << " over " << result.metrics.size() << " metrics)";
    out << " (Mann-Whitney U, " << m.test.n2 << " vs " << m.test.n1 << " " << m.unit
        << (m.unit == "runs" ? ", the median of each" : "")
        << (m.too_few_samples ? "; too few for the test, decided on the tolerance and floor" : "") << ")\n";
  };
  for (const MetricCheck& m : result.metrics)
    if (m.regressed) metric_line(m, "REGRESSION");
  for (const MetricCheck& m : result.metrics)
    if (m.excused) metric_line(m, "WARNING, slower");
  if (result.witness) out << result.witness->line() << "\n";
  if (result.witness && result.witness->excuses())
    out << "warning: a stored baseline cannot tell a slower machine from a slower build beyond this; to time the "
           "change, run both builds side by side: check --against BASE_BINARY\n";
  for (const CounterDifference& d : result.counters)
    out << "CHANGED counter " << d.name << ": " << d.baseline << " -> " << d.current << " per frame\n";
  for (const std::string& name : result.counters_missing)
    out << "CHANGED counter " << name << ": in the baseline, missing here\n";
  if (result.digest_differs())
    out << "CHANGED digest: " << result.baseline_digest << " -> " << result.current_digest
        << " (the last frame's poses or skinned vertices differ)\n";
  else if (result.baseline_digest != result.current_digest)
    out << "digest " << result.baseline_digest << " -> " << result.current_digest << " " << result.digest_note()
        << "\n";
  if (result.regressed()) return out.str();
  // One line: every metric's verdict, then the exact checks.
  out << "ok";
  for (const MetricCheck& m : result.metrics) {
    out << " " << m.metric << " " << metric_value_text(m, m.baseline.median) << " -> "
        << metric_value_text(m, m.current.median) << " " << m.value_unit << " (" << percent(m.change)
        << ", p = " << p_value_text(m.p_adjusted);
    if (m.excused)
      out << ", slower beyond " << tolerance << ": a warning, the same instructions per frame";
    else if (m.beyond_tolerance && !m.beyond_floor)
      out << ", beyond " << tolerance << " but under the floor of " << metric_value_text(m, m.floor_ms) << " "
          << m.value_unit;
    else if (m.beyond_tolerance)
      out << ", beyond " << tolerance << " but not significant";
    else if (significantly_faster(m, options))
      out << ", faster";
    else if (m.change < -options.tolerance)
      out << ", faster beyond " << tolerance << " but not significant";
    else
      out << ", within " << tolerance;
    out << ");";
  }
  if (!result.metrics.empty())
    out << " " << result.metrics.front().test.n2 << " vs " << result.metrics.front().test.n1 << " "
        << result.metrics.front().unit << ";";
  if (!options.compare_work)
    out << " counters and digest not compared\n";
  else if (result.baseline_digest != result.current_digest)
    out << " counters match, digest not compared (" << result.digest_not_compared_why() << ")\n";
  else
    out << " counters and digest match\n";
  return out.str();
}

}  // namespace crowdprof

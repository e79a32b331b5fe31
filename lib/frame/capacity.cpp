#include "frame/capacity.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "measuring/stats.h"

namespace crowdprof {

namespace {

bool fits(const CapacityRule& rule, const CapacityPoint& point) {
  return point.median_ms <= rule.budget_ms;
}

// The bracket the search narrows: the smallest N that did not fit (0: none
// yet) and the largest N below it that did (0: none). Later points at the
// same N replace earlier ones.
struct Bracket {
  const CapacityPoint* fit = nullptr;
  const CapacityPoint* fail = nullptr;
};

Bracket bracket(const CapacityRule& rule, std::span<const CapacityPoint> tried) {
  Bracket b;
  for (const CapacityPoint& p : tried)
    if (!p.partial && !fits(rule, p) && (!b.fail || p.n <= b.fail->n)) b.fail = &p;
  for (const CapacityPoint& p : tried)
    if (!p.partial && fits(rule, p) && (!b.fail || p.n < b.fail->n) && (!b.fit || p.n >= b.fit->n)) b.fit = &p;
  return b;
}

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

SettingText CapacityRule::Validate() const {
  if (!(budget_ms > 0) || !std::isfinite(budget_ms)) return "{budget} must be a number of milliseconds above 0";
  if (start < 1) return "{start} must be at least 1";
  if (cap < 1) return "{max_characters} must be at least 1";
  if (start > cap) return "{start} must not exceed {max_characters} (" + std::to_string(cap) + ")";
  if (!(resolution >= 0 && resolution < 1)) return "{precision} must be a fraction from 0 to below 1";
  return {};
}

size_t next_capacity_n(const CapacityRule& rule, std::span<const CapacityPoint> tried) {
  Bracket b = bracket(rule, tried);
  if (!b.fit && !b.fail) return std::min(rule.start, rule.cap);
  size_t lo = b.fit ? b.fit->n : 0;
  if (!b.fail) {
    // Growing: doubling until a size does not fit or the cap does.
    if (lo >= rule.cap) return 0;
    return std::min(rule.cap, lo * 2);
  }
  size_t hi = b.fail->n;
  if (hi <= 1) return 0;  // not even one copy fits
  size_t width = std::max<size_t>(1, static_cast<size_t>(std::floor(rule.resolution * static_cast<double>(lo))));
  if (hi - lo <= width) return 0;
  return lo + (hi - lo) / 2;
}

CapacityResult capacity_result(const CapacityRule& rule, std::span<const CapacityPoint> tried) {
  CapacityResult result;
  Bracket b = bracket(rule, tried);
  if (b.fit) result.fit = *b.fit;
  if (b.fail) result.fail = *b.fail;
  result.capped = b.fit && !b.fail && b.fit->n >= rule.cap;
  std::vector<const CapacityPoint*> sorted;
  for (const CapacityPoint& p : tried)
    if (!p.partial) sorted.push_back(&p);
  std::sort(sorted.begin(), sorted.end(), [](const CapacityPoint* x, const CapacityPoint* y) { return x->n < y->n; });
  double highest = 0;  // the highest median of the smaller sizes so far
  for (const CapacityPoint* p : sorted) {
    if (p->median_ms < 0.9 * highest) result.non_monotonic = true;
    highest = std::max(highest, p->median_ms);
  }
  return result;
}

std::string CapacityMetric::name() const {
  return category ? std::string(category_name(*category)) : "frame";
}

std::optional<CapacityMetric> parse_capacity_metric(const std::string& text) {
  std::string wanted = lower(text);
  if (wanted == "frame") return CapacityMetric{};
  for (size_t c = 0; c < kCategoryCount; ++c) {
    auto category = static_cast<Category>(c);
    if (wanted == lower(std::string(category_name(category))) || wanted == category_column(category))
      return CapacityMetric{category};
  }
  return std::nullopt;
}

std::vector<double> metric_values(const Result& report, const CapacityMetric& metric) {
  std::vector<double> values;
  for (const FrameRecord& f : report.frame_records)
    values.push_back(metric.category ? f.times[*metric.category] : f.times.total_ms());
  return values;
}

CapacityPoint capacity_point(const Result& report, const CapacityMetric& metric, size_t n, size_t round) {
  std::vector<double> frames;
  for (const FrameRecord& f : report.frame_records) frames.push_back(f.times.total_ms());
  Summary s = summarize(metric_values(report, metric));
  CapacityPoint p;
  p.n = n;
  p.median_ms = s.median;
  p.p95_ms = s.p95;
  p.p99_ms = s.p99;
  p.min_ms = s.min;
  p.max_ms = s.max;
  p.frame_median_ms = summarize(frames).median;
  p.frames = report.frame_records.size();
  p.round = round;
  p.partial = report.partial;
  p.digest = report.digest;
  return p;
}

CapacityRun run_capacity(std::vector<ModeCapacity> modes, const CapacityMetric& metric,
                         const CapacityMeasure& measure) {
  CapacityRun run;
  run.metric = metric;
  for (size_t round = 1;; ++round) {
    std::vector<size_t> active, ns;
    for (size_t m = 0; m < modes.size(); ++m)
      if (size_t n = next_capacity_n(modes[m].rule, modes[m].tried)) {
        active.push_back(m);
        ns.push_back(n);
      }
    if (active.empty()) break;
    std::vector<Result> reports = measure(active, ns);
    bool partial = false;
    for (size_t k = 0; k < active.size() && k < reports.size(); ++k) {
      ModeCapacity& mode = modes[active[k]];
      mode.tried.push_back(capacity_point(reports[k], metric, ns[k], round));
      mode.threads = reports[k].run.threads;
      partial = partial || reports[k].partial;
      // Only the reports at the bracket's ends are kept: a run may try many sizes.
      CapacityResult now = capacity_result(mode.rule, mode.tried);
      if (now.fit && now.fit->n == ns[k] && !reports[k].partial) mode.fit_run = reports[k];
      if (now.fail && now.fail->n == ns[k] && !reports[k].partial) mode.fail_run = reports[k];
    }
    if (!run.first && !reports.empty()) run.first = reports.front();
    if (reports.size() != active.size()) throw std::logic_error("capacity: a round measured the wrong number of modes");
    if (partial) {
      run.partial = true;
      break;
    }
  }
  for (ModeCapacity& mode : modes) {
    mode.result = capacity_result(mode.rule, mode.tried);
    // Bisection never moves a bracket's end outside it, so these are the ends' reports.
    if (!mode.result.fit || !mode.fit_run || mode.fit_run->run.characters != mode.result.fit->n) mode.fit_run.reset();
    if (!mode.result.fail || !mode.fail_run || mode.fail_run->run.characters != mode.result.fail->n)
      mode.fail_run.reset();
  }
  run.modes = std::move(modes);
  return run;
}

}  // namespace crowdprof

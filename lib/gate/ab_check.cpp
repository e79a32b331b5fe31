#include "gate/ab_check.h"

#include <cmath>
#include <stdexcept>

#include "result/result_codec.h"
#include "gate/regression.h"
#include "measuring/stats.h"

namespace crowdprof {

AbProcess ab_process(const Result& result) {
  AbProcess process;
  // A frame whose GPU time was not read back holds NaN, which the median skips.
  for (const std::string& key : recorded_metrics(result)) process.median_ms[key] = metric_median(result, key);
  process.digest = result.digest;
  process.digest_cpu_vertices = result.digest_cpu_vertices;
  process.vertex_order = result.vertex_order;
  process.counters = result.counters;
  return process;
}

bool AbResult::regressed() const {
  if (work.compared && !work.equal) return true;
  for (const AbMetric& metric : metrics)
    if (metric.regressed) return true;
  return false;
}

namespace {

double median_of(const AbProcess& process, const std::string& key) {
  auto found = process.median_ms.find(key);
  if (found == process.median_ms.end()) throw std::invalid_argument("a process has no samples of " + key);
  return found->second;
}

bool same_counters(const RecordedCounters& a, const RecordedCounters& b) {
  if (a.present != b.present) return false;
  for (const CounterField& field : kCounterFields)
    if (a.values.*field.member != b.values.*field.member) return false;
  return true;
}

AbWork compare_work(const std::vector<AbGroup>& groups) {
  AbWork work;
  work.compared = true;
  const AbProcess& base = groups.front().base[0];
  const AbProcess& current = groups.front().current[0];
  work.base_digest = base.digest;
  work.current_digest = current.digest;
  for (const AbGroup& group : groups)
    for (int i = 0; i < 2; ++i) {
      if (group.base[i].digest != base.digest || !same_counters(group.base[i].counters, base.counters))
        work.inconsistent = "base";
      if (group.current[i].digest != current.digest || !same_counters(group.current[i].counters, current.counters))
        work.inconsistent = "current";
    }
  for (size_t i = 0; i < kCounterFields.size(); ++i) {
    if (!base.counters.present[i]) continue;
    uint64_t was = base.counters.values.*kCounterFields[i].member;
    uint64_t now = current.counters.present[i] ? current.counters.values.*kCounterFields[i].member : 0;
    if (now != was) work.counters.push_back({std::string(kCounterFields[i].name), was, now});
  }
  const bool reordered = vertex_orders_differ(base.vertex_order, current.vertex_order,
                                              base.digest_cpu_vertices || current.digest_cpu_vertices);
  if (reordered && work.base_digest != work.current_digest)
    work.digest_note = "not compared: " + vertex_order_note(base.vertex_order, current.vertex_order);
  work.equal = (work.base_digest == work.current_digest || !work.digest_note.empty()) && work.counters.empty() &&
               work.inconsistent.empty();
  return work;
}

}  // namespace

AbResult judge_ab(const std::vector<AbGroup>& groups, const AbOptions& options) {
  if (groups.empty()) throw std::invalid_argument("an A/B needs at least one group");
  AbResult result;
  std::vector<double> base_frames;
  for (const AbGroup& group : groups)
    for (const AbProcess& process : group.base) base_frames.push_back(median_of(process, "frame_ms"));
  const double floor = floor_ms(options.floor, quantile(base_frames, 0.5));
  for (const std::string& key : options.metrics) {
    AbMetric metric;
    metric.metric = key;
    metric.floor_ms = floor;
    std::vector<double> base_all, current_all, log_ratios;
    for (const AbGroup& group : groups) {
      double base = std::sqrt(median_of(group.base[0], key) * median_of(group.base[1], key));
      double current = std::sqrt(median_of(group.current[0], key) * median_of(group.current[1], key));
      for (int i = 0; i < 2; ++i) {
        base_all.push_back(median_of(group.base[i], key));
        current_all.push_back(median_of(group.current[i], key));
      }
      // A category that took no time in both builds has no ratio: it is equal.
      double ratio = base > 0 ? current / base : (current > 0 ? INFINITY : 1.0);
      metric.ratios.push_back(ratio);
      log_ratios.push_back(std::isfinite(ratio) && ratio > 0 ? std::log(ratio) : (ratio > 0 ? 50.0 : -50.0));
    }
    MedianInterval log_change = bootstrap_median(log_ratios, options.confidence);
    metric.change = {std::exp(log_change.median) - 1, std::exp(log_change.low) - 1, std::exp(log_change.high) - 1};
    metric.base_ms = quantile(base_all, 0.5);
    metric.current_ms = metric.base_ms * (1 + metric.change.median);
    metric.current_median_ms = quantile(current_all, 0.5);
    metric.test = wilcoxon_signed_rank(log_ratios);
    result.metrics.push_back(std::move(metric));
  }
  std::vector<double> p;
  for (const AbMetric& metric : result.metrics) p.push_back(metric.test.p);
  std::vector<double> adjusted = holm_adjust(p);
  for (size_t i = 0; i < result.metrics.size(); ++i) {
    AbMetric& metric = result.metrics[i];
    metric.p_adjusted = adjusted[i];
    metric.significant = metric.p_adjusted < options.alpha;
    metric.beyond_tolerance = std::fabs(metric.change.median) > options.tolerance;
    metric.beyond_floor = std::fabs(metric.current_ms - metric.base_ms) > metric.floor_ms;
    bool shifted = metric.significant && metric.beyond_tolerance && metric.beyond_floor;
    metric.regressed = shifted && metric.change.median > 0;
    metric.improved = shifted && metric.change.median < 0;
  }
  if (options.compare_work) result.work = compare_work(groups);
  return result;
}

}  // namespace crowdprof

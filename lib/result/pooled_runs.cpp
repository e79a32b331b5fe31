#include "result/pooled_runs.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace crowdprof {

Result median_run(std::vector<Result> runs, const std::string& key) {
  if (runs.empty()) throw std::invalid_argument("median_run of no runs");
  std::vector<std::pair<double, size_t>> medians;
  for (size_t i = 0; i < runs.size(); ++i) {
    if (!metric_samples(runs[i], key)) throw std::invalid_argument("a run has no samples of " + key);
    medians.emplace_back(metric_median(runs[i], key), i);
  }
  std::sort(medians.begin(), medians.end());
  return std::move(runs[medians[(medians.size() - 1) / 2].second]);
}

Result pooled_runs(std::vector<Result> runs, const std::string& key) {
  PooledRuns pool;
  pool.count = runs.size();
  for (const std::string& metric : recorded_metrics(runs.at(0))) {
    bool everywhere = std::all_of(runs.begin(), runs.end(), [&](const Result& r) { return metric_samples(r, metric); });
    if (!everywhere) continue;
    for (const Result& run : runs) pool.median_ms[metric].push_back(metric_median(run, metric));
  }
  bool pids = std::all_of(runs.begin(), runs.end(), [](const Result& r) { return r.pid.has_value(); });
  bool starts = std::all_of(runs.begin(), runs.end(), [](const Result& r) { return r.started_s.has_value(); });
  for (Result& run : runs) {
    if (pids) pool.pids.push_back(*run.pid);
    if (starts) pool.started_s.push_back(*run.started_s);
    run.pid.reset();
    run.started_s.reset();
  }
  Result pooled = median_run(std::move(runs), key);
  pooled.runs = std::move(pool);
  return pooled;
}

}  // namespace crowdprof

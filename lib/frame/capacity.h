// `crowdprof capacity`: the largest crowd whose median frame (or one
// category's median) fits a time budget, per mode. The search over the crowd
// size N is a pure function of the points measured so far, so it is tested
// against a fake cost curve; the measuring is the compare machinery
// (run_interleaved), one round of every mode still searching at a time.
//
// The search rule (docs/capacity.md): N = start, then doubling while N fits,
// up to the cap; after the first N that does not fit, bisection between the
// largest N that fits and the smallest N above it that does not, until the
// two are at most max(1, floor(resolution * fit)) apart. It assumes time grows
// with N; where the medians say otherwise the search still ends (on one
// boundary) and the result says so (non_monotonic).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/errors.h"

#include "result/result.h"
#include "result/result_document.h"

namespace crowdprof {

struct CapacityRule {
  double budget_ms = 1000.0 / 60.0;  // a point fits when its median is <= this; 60 fps, as the charts draw it
  size_t start = 10;                 // the first N tried
  size_t cap = 100'000;              // the largest N tried
  double resolution = 0.05;          // the bracket's width at which the search stops, relative to the fit

  // Empty when the rule can run, else why not, naming the setting: "{budget}
  // must be a number of milliseconds above 0" (cli/ spells it --budget).
  SettingText Validate() const;
};

// The next N to measure after `tried` (in any order; partial points are
// ignored), or 0 when the search is over.
size_t next_capacity_n(const CapacityRule& rule, std::span<const CapacityPoint> tried);

// What the search found. fit: the largest N that fits below the smallest N
// that does not (fail); no fit when even the smallest N tried did not fit
// (down to 1), no fail when the cap fits (capped).
struct CapacityResult {
  std::optional<CapacityPoint> fit, fail;
  bool capped = false;
  // Some larger N had a median more than 10% below a smaller N's (noise larger
  // than the step, or a cost that does not grow with N): the boundary found is
  // one of several.
  bool non_monotonic = false;
};
CapacityResult capacity_result(const CapacityRule& rule, std::span<const CapacityPoint> tried);

// One mode's search and what it measured.
struct ModeCapacity {
  std::string mode;
  int threads = 1;                   // as its runs reported
  CapacityRule rule;                 // its cap may be lower than the user's: the memory
  std::vector<CapacityPoint> tried;  // in the order measured
  CapacityResult result;
  // What was measured at result.fit and at result.fail (the reports, for the
  // HTML page and the JSON's "runs").
  std::optional<Result> fit_run, fail_run;
};

// Measures a round: every mode still searching, `ns[m]` copies for mode
// `modes[m]` (indices into the run's modes), side by side; one report per mode, in order.
using CapacityMeasure = std::function<std::vector<Result>(std::span<const size_t> modes, std::span<const size_t> ns)>;

// The metric of a report's frames: the frame time, or one category's.
struct CapacityMetric {
  std::optional<Category> category;  // none: the whole frame
  std::string name() const;          // "frame" or the category's name
};
// "frame", or a category by its name or its CSV column, any case ("Animations",
// "gpu_latency"); none when it is neither.
std::optional<CapacityMetric> parse_capacity_metric(const std::string& text);

// The metric of each of a report's frames, in order.
std::vector<double> metric_values(const Result& report, const CapacityMetric& metric);

// The point a report measured at N.
CapacityPoint capacity_point(const Result& report, const CapacityMetric& metric, size_t n, size_t round);

struct CapacityRun {
  std::vector<ModeCapacity> modes;
  CapacityMetric metric;
  size_t block = 10, frames = 0, warmup = 0;  // of every point (set by the caller, for the report)
  bool partial = false;                       // a round was cut short (^C): the results are what was found before it
  std::optional<Result> first;                // the first report measured, for the run's description
};

// Runs every mode's search, one round of measurements at a time, until each
// is over or a round comes back partial.
CapacityRun run_capacity(std::vector<ModeCapacity> modes, const CapacityMetric& metric, const CapacityMeasure& measure);

}  // namespace crowdprof

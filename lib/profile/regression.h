// `crowdprof check`: did this change make things slower, or change the work?
// Timing is judged on the per-frame samples of two results (bench --json) with
// a tolerance and the Mann-Whitney U test together, so noise alone does not
// fail; the deterministic counters and the digest are compared exactly.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "profile/mann_whitney.h"
#include "profile/stats.h"

namespace crowdprof {

// The "crowdprof.format" that report.cpp writes and check reads.
inline constexpr int kResultFormat = 1;

// "10%" or "0.1" (both a tenth) to a fraction; UsageError for anything else:
// words, negative values, NaN, more than 1000%.
double parse_tolerance(std::string_view text);

// The metric's key in "samples": "frame" gives "frame_ms"; a category is named
// as the BGE printed it or as a CSV column ("Animations", "animations",
// "GPU Latency", "gpu_latency"). UsageError listing the choices otherwise.
std::string resolve_metric(std::string_view name);

// Reads a crowdprof JSON file: InputError naming `path` when it is missing, not
// a regular file, larger than 2 GiB, empty, truncated, not JSON or not an
// object. What it holds is not checked (validate_result, bench_results_in).
nlohmann::json read_json_file(const std::string& path);

// Reads and validates a result written by bench --json (see validate_result).
// InputError naming `path` when the file is unreadable, empty, not JSON or
// truncated, or not a result this version can read.
nlohmann::json read_result(const std::string& path);

// InputError("<path>: ...") unless `doc` is a bench result of kResultFormat with
// the scene, the mode, per-frame samples for the frame and every category (as
// many as "frames", finite, not negative), the counters and a digest.
void validate_result(const nlohmann::json& doc, const std::string& path);

// InputError naming the baseline and the first field that differs when the two
// results are not runs of the same thing: the scene (file name, character,
// characters, joints, vertices, actions, seed, camera), the mode and its
// switches, frames, warm-up and simulated fps. Counters and digest depend on all
// of these, so comparing them across a difference would mean nothing.
void require_same_run(const nlohmann::json& baseline, const nlohmann::json& current, const std::string& baseline_path);

// A result as written to `result_path`: its scene file (and those of a compare
// result's runs) stored relative to the result's folder, marked
// "file_from": "result", so that the result can be checked from any folder and
// moved with its scene. A "#skin=N" suffix is kept.
nlohmann::json with_paths_relative_to(nlohmann::json result, const std::string& result_path);

// The scene file a result read from `result_path` recorded, as a path usable
// from here: resolved from the result's folder when it was stored relative to
// it; as recorded for older results (relative to the folder they were made in),
// unless only the result's folder has it.
std::string recorded_scene_file(const nlohmann::json& result, const std::string& result_path);

// What differs without stopping the comparison: a note per difference of
// thread count or GL backend, and one "warning: " line for another machine or
// build (CPU model, cores, build type, compiler, SIMD target). Lines for stderr
// after "crowdprof: note: ", except the warning, which has its own prefix.
std::vector<std::string> comparison_notes(const nlohmann::json& baseline, const nlohmann::json& current);

// The smallest slowdown that can fail a check, however significant: a fixed
// time, or a fraction of the baseline's median frame time. It keeps changes far
// below anything a user would notice (a category of microseconds moving by a
// microsecond) from failing CI.
struct Floor {
  double ms = 0;                    // when fraction is 0
  double fraction_of_frame = 0.02;  // of the baseline's median frame time
};

// "0.05ms", "50us" or "2%" (of the baseline's median frame); UsageError naming
// --floor for anything else.
Floor parse_floor(std::string_view text);

// The floor in milliseconds for a baseline whose median frame is `frame_ms`.
double floor_ms(const Floor& floor, double frame_ms);

// Default tolerance: a 10% slowdown of the frame, real work added, must fail
// (docs/compare-and-check.md measures how often it does), so the tolerance sits
// below it, and noise that moves a median by a few percent does not.
inline constexpr double kDefaultTolerance = 0.07;

struct CheckOptions {
  // Keys of "samples" (resolve_metric). CPU time by default: on a machine shared
  // with other jobs the wall-clock frame swings by half while the work does not
  // (docs/compare-and-check.md has the measurement).
  std::vector<std::string> metrics = {"cpu_ms"};
  double tolerance = kDefaultTolerance;  // a slowdown of the median beyond this fraction...
  double alpha = 0.05;      // ...that the U test finds significant at this level (Holm-corrected over metrics)...
  Floor floor;              // ...and larger than this
  // False only to measure the gate itself (check --timings-only): timings of
  // two different runs, counters and digest not compared.
  bool compare_work = true;
};

// Of several results of one run, the one whose median of samples `key` is the
// median (the lower middle of an even count): what --update-baseline records.
// `runs` must not be empty and each must hold samples `key`.
nlohmann::json median_run(std::vector<nlohmann::json> runs, const std::string& key);

// Most runs a result may pool (check --runs).
inline constexpr size_t kMaxRuns = 100;

// Several runs of one scene, each measured in a process of its own, as one
// result: the median run (median_run by `key`) with a "runs" section:
// {"count": n, "median_ms": {samples key: [the median of each run]}, "pids":
// [each run's process id], "started_s": [when each run started, seconds after
// the first]} (pids and started_s when every run has a "pid" or "started_s",
// which is moved there). check_results judges runs instead of frames when both results pool
// at least kMannWhitneyMinSamples runs. `runs` must not be empty.
nlohmann::json pooled_runs(std::vector<nlohmann::json> runs, const std::string& key);

// How a samples key is named to users: "cpu_ms" as "cpu", "frame_ms" as
// "frame", a category by its key ("animations_ms").
std::string metric_display_name(const std::string& key);

struct MetricCheck {
  std::string metric;  // as the user named it: "frame", "Animations"
  Summary baseline, current;
  double baseline_iqr = 0, current_iqr = 0;  // interquartile range, ms
  double change = 0;                         // of the median, a fraction; +0.2 is 20% slower
  double floor_ms = 0;                       // the floor it was judged against
  MannWhitney test;                          // current against baseline
  double p_adjusted = 1;                     // test.p, Holm-corrected for the metrics tested together
  bool beyond_tolerance = false, beyond_floor = false, significant = false;
  bool too_few_samples = false;  // under kMannWhitneyMinSamples: decided on the tolerance and floor alone
  std::string unit = "frames";   // what was compared: each frame, or the median of each run ("runs")
  bool regressed = false;
};

struct CounterDifference {
  std::string name;
  uint64_t baseline = 0, current = 0;
};

struct CheckResult {
  std::vector<MetricCheck> metrics;
  std::vector<CounterDifference> counters;  // only those that differ
  std::vector<std::string> counters_missing;  // in the baseline, not in the current result
  std::string baseline_digest, current_digest;
  bool digest_differs() const { return baseline_digest != current_digest; }
  bool regressed() const;
};

// Judges one metric's samples: regressed when the median grew by more than the
// tolerance and by more than `floor` ms, and the U test says the shift is
// significant (or, with too few samples for the test, on the tolerance and the
// floor alone). `tested` is how many metrics are judged together, for
// adjust_holm; alone, p_adjusted is p.
MetricCheck check_metric(std::string metric, std::span<const double> baseline, std::span<const double> current,
                         const CheckOptions& options, double floor = 0);

// Holm's step-down correction over metrics tested at once: with m metrics, the
// k-th smallest p-value (from 0) is multiplied by m - k, made monotone, and
// capped at 1. Sets p_adjusted, significant and regressed again.
void adjust_holm(std::vector<MetricCheck>& metrics, const CheckOptions& options);

// Every key of "samples" (frame_ms, then the categories): --metric all.
std::vector<std::string> all_metrics();

// Both documents validated and of the same run (require_same_run). When both
// pool kMannWhitneyMinSamples runs or more (pooled_runs), each metric compares
// the medians of their runs; otherwise the frames of each (of the median run).
// The floor is resolved against the baseline's median frame, and the metrics
// are Holm-corrected together.
CheckResult check_results(const nlohmann::json& baseline, const nlohmann::json& current, const CheckOptions& options);

// What stdout shows: a line per regressed metric or changed counter (metric,
// both medians, their IQRs, the change and the p-value), or one summary line
// when nothing regressed.
std::string format_check(const CheckResult& result, const CheckOptions& options);

}  // namespace crowdprof

// `check` as steps: the plan (this file: what the gate compares, how many
// runs, how they are spread), then the run spec (frame/run_spec.h: defaults,
// scene file, baseline, command line), the runs, the gate (regression.h) and
// the outputs. The plan is a pure function of what the user asked, so it is
// tested without a process.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gate/regression.h"

namespace crowdprof {

// What the user asked of `check`, as typed.
struct CheckRequest {
  std::vector<std::string> metrics = {"calibrated"};  // "all", "frame", "calibrated", "cpu", a category
  std::string tolerance = "7%";
  bool tolerance_given = false;  // else the metric's own default (instructions: 1%)
  std::string floor = "2%";
  double alpha = 0.05;
  std::optional<long long> runs;   // unset: 8, or 20 when recording a baseline
  std::optional<double> spread_s;  // unset: 0 (back to back)
  bool update_baseline = false;
  bool timings_only = false;
  bool has_result = false;  // --result: read, not run
  bool ab = false;          // --against: an A/B of two builds, not a stored baseline
  // The files of timed runs the command line asked for (--csv, --html, --svg,
  // --trace, --screenshot), which counted runs do not write.
  std::vector<std::string> timed_outputs;
};

// A baseline is held against every later check, so its luck counts many
// times: it gets more runs than a check (docs/compare-and-check.md).
inline constexpr long long kCheckRuns = 8, kBaselineRuns = 20;

// --metric instructions: the instructions per measured frame (measuring/
// instruction_counter.h), a count of work that the machine's speed does not
// move, so one run is enough and the tolerance is small.
inline constexpr const char* kInstructionsMetric = "instructions";
inline constexpr double kInstructionTolerance = 0.01;

struct CheckPlan {
  CheckOptions
      gate;  // metrics (samples keys, no repeats, or kInstructionsMetric alone), tolerance, floor, alpha, work compared
  size_t runs = kCheckRuns;  // each a process of its own
  double spread_s = 0;       // the runs start this many seconds apart in all
  bool update_baseline = false;
  // The runs are counted, not timed (kInstructionsMetric): the one metric
  // whose runs are other processes, judged without a test of significance.
  bool counted() const { return !gate.metrics.empty() && gate.metrics.front() == kInstructionsMetric; }
};

// The plan, every value checked: SettingError naming the setting (tolerance,
// floor, alpha, runs, spread, metric) or UsageError for options that cannot go
// together (the counted metric with timed files or an A/B among them).
CheckPlan plan_check(const CheckRequest& request);

// The metrics a stored-baseline check compares, once both results are known,
// and the notes that say why they changed. The calibrated frame compares only
// between runs of the same probe; CPU time only between runs that both ran the
// probe or both did not (its workers spin on into the next frame).
struct GateMetrics {
  std::vector<std::string> metrics;
  std::vector<std::string> notes;  // one line each, for stderr after "note: "
};
// `named`: the user gave --metric, so nothing is swapped: a named calibrated
// metric over two probe versions is an InputError naming `baseline_path`.
// Unnamed, the default calibrated frame falls back to CPU time where both ran
// the probe alike (or neither did), else to the frame. `current_name` names the
// other result in notes ("the run" or its file).
GateMetrics gate_metrics(const Result& baseline, const Result& current, std::vector<std::string> metrics, bool named,
                         const std::string& baseline_path, const std::string& current_name);

}  // namespace crowdprof

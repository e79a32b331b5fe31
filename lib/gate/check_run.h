// `check` run: the plan (check_plan.h), the runs (each a process of its own,
// spread, cut short by ^C with a partial result), the gate (regression.h, or
// ab_check.h for an A/B of two builds), and the confirmation of a timed
// failure. What it returns is written and printed by reports/check_report.h.
#pragma once

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "frame/bench_setup.h"
#include "frame/run_spec.h"
#include "gate/ab_check.h"
#include "gate/check_plan.h"
#include "gate/regression.h"
#include "result/result.h"

namespace crowdprof {

// Everything a `check` was asked, as plain values: what check_plan.h plans
// from, the files, the runs' settings and the outputs.
struct CheckRun {
  CheckRequest plan;          // metrics, tolerance, floor, alpha, runs, spread, ...
  bool metric_given = false;  // the metrics were named: nothing is swapped for them
  std::string baseline;       // the stored result compared against (or written, plan.update_baseline)
  std::string result;         // a result to read instead of running
  std::string against;        // the base build's binary: an A/B instead of a stored baseline
  long long groups = static_cast<long long>(kAbGroups);  // A/B: ABBA groups of four processes
  // A timed failure with the work unchanged is measured this many times more
  // before it fails (each the same runs): a machine that slowed for seconds
  // rarely does so twice.
  long long confirm = 1;
  // Seconds a confirmation spreads its runs over: a slow spell of the machine
  // lasts seconds to a minute, and runs spread over one sample both sides of it.
  double confirm_spread = 60;
  // A timed baseline also holds instructions per frame, counted once when it
  // is recorded (hardware counter, else callgrind), so that a check that runs
  // slower with the same count can tell a changed machine from a slower
  // build (gate/work_witness.h). --count-work off skips it.
  bool count_work = true;

  SpecLayer command_line;                                   // the settings given, the scene file among them
  SpecLayer defaults{SpecLayer::Source::Defaults, "", {}};  // the command's own
  bool quiet = false;
  // Every output the command declared, as given ("--json", "--junit", ...;
  // files.path("--csv")): checked before any run, written from here.
  OutputFiles files;
  // The options given, as spelled ("--csv"): some cannot go with an A/B or a
  // counted metric.
  std::set<std::string> given;
  // A/B: --metric, --tolerance ... as given, for the command that reproduces it.
  std::vector<std::string> gate_arguments;

  // Called in a catch block of a measured run's process: prints its error and
  // returns the exit status (the parent exits with it).
  std::function<int()> report_exception;
  // Called in each timed run's process with its result: the files of one run
  // (--csv, of the last run, as reports/check_report.h sets it).
  std::function<void(const Result&)> each_run;
  // A setting as the user typed it ("threads" as "--threads"), for messages.
  std::function<std::string(std::string_view)> option_name;

  bool was_given(const std::string& option) const { return given.count(option) > 0; }
};

// The instructions per frame of a counted check (--metric instructions),
// judged against the tolerance alone: the count does not vary with the
// machine, so no test of significance.
struct CountCheck {
  double base = 0, current = 0;  // per measured frame
  double change = 0;             // a fraction: +0.1 is 10% more
  bool slower = false, faster = false;
  std::string origin;  // what counted: source, SIMD target, compiler, threads
};

// A/B: the builds, their groups' verdict and its record.
struct AbRun {
  AbResult result;
  AbOptions gate;
  std::string base_binary, base_version, current_binary, current_version;
  std::vector<std::string> bench_args;  // as both builds ran them
  nlohmann::json processes = nlohmann::json::array();
  double wall_s = 0;
  Result last_base, last_current;   // the last run of each build
  std::string reproduce;            // the check command that reproduces it
  nlohmann::json document() const;  // --json
};

struct CheckOutcome {
  enum class Kind { Interrupted, BaselineWritten, Gated, Counted, Ab };
  Kind kind = Kind::Interrupted;
  CheckPlan plan;  // its gate's metrics as judged
  std::optional<Result> baseline;
  Result current;
  CheckResult result;       // Gated; Counted: the work alone
  CountCheck count;         // Counted
  std::optional<AbRun> ab;  // Ab
  double wall_s = 0;        // seconds run_check took
};

// Runs the check: UsageError, SettingError or InputError for what cannot be
// run (before any run where it can be known before), std::runtime_error for a
// run that failed, ChildFailed (gate/processes.h) for one that said why.
CheckOutcome run_check(const CheckRun& request);

}  // namespace crowdprof

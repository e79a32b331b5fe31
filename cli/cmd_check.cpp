// `crowdprof check`: runs a bench (or reads a result of bench --json) and
// compares it with a baseline: exit 1 when a metric regressed beyond the
// tolerance and significantly, or when the work done (counters, digest)
// changed; exit 0 with a one-line summary otherwise. The runner is in
// lib/gate/check_run.h, the gate in lib/gate/regression.h, its outputs in
// lib/reports/check_report.h.
#include <algorithm>
#include <functional>
#include <iostream>
#include <memory>
#include <string_view>

#include "base/number_text.h"
#include "base/switch_table.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "cli/usage_errors.h"
#include "gate/check_run.h"
#include "reports/check_report.h"

namespace {

using namespace crowdprof;

struct CheckCliOptions {
  BenchCliOptions bench;
  std::string baseline, result;
  std::vector<std::string> metrics = {"calibrated"};
  std::string tolerance = "7%";
  std::string floor = "2%";
  long long runs = kCheckRuns;  // the plan's default: more with --update-baseline
  // Runs spread over this many seconds sample several moments of a machine
  // shared with other jobs. Not by default: on the development VM a run that
  // starts after an idle wait is often 20-45% slower (docs/compare-and-check.md).
  double spread = 0;
  double alpha = 0.05;
  bool update = false;
  bool timings_only = false;
  std::string svg;
  std::string against;  // the base build's binary: an A/B instead of a stored baseline
  long long groups = static_cast<long long>(kAbGroups);
  // A timed failure with the work unchanged is measured this many times more
  // before it fails (each the same runs): a machine that slowed for seconds
  // rarely does so twice.
  long long confirm = 1;
  // Seconds a confirmation spreads its runs over: a slow spell of the machine
  // lasts seconds to a minute, and runs spread over one sample both sides of it.
  double confirm_spread = 60;
  std::string count_work = "on";
  std::string junit, markdown;
  CLI::App* command = nullptr;  // to tell options given from defaults
};

// Everything the command line decided, as the library's plain request.
CheckRun request_of(const CheckCliOptions& o) {
  CheckRun r;
  r.plan.metrics = o.metrics;
  r.plan.tolerance = o.tolerance;
  r.plan.tolerance_given = o.command->count("--tolerance") > 0;
  r.plan.floor = o.floor;
  r.plan.alpha = o.alpha;
  if (o.command->count("--runs") > 0) r.plan.runs = o.runs;
  if (o.command->count("--spread") > 0) r.plan.spread_s = o.spread;
  r.plan.update_baseline = o.update;
  r.plan.timings_only = o.timings_only;
  r.plan.has_result = !o.result.empty();
  r.metric_given = o.command->count("--metric") > 0;
  r.baseline = o.baseline;
  r.result = o.result;
  r.against = o.against;
  r.groups = o.groups;
  r.confirm = o.confirm;
  r.confirm_spread = o.confirm_spread;
  r.count_work = o.count_work == "on";
  r.command_line = command_line_layer(o.bench);
  r.defaults = o.bench.defaults;
  r.quiet = o.bench.quiet;
  r.files = o.bench.outputs.files();
  for (const CLI::Option* option : o.command->get_options())
    if (option->count() > 0) {
      for (const std::string& name : option->get_lnames()) r.given.insert("--" + name);
      for (const std::string& name : option->get_snames()) r.given.insert("-" + name);
    }
  for (const char* option : {"--metric", "--tolerance", "--floor", "--alpha", "--groups"})
    if (const CLI::Option* given = o.command->get_option(option); given->count() > 0) {
      r.gate_arguments.push_back(option);
      std::string values;
      for (const std::string& value : given->results()) values += (values.empty() ? "" : ",") + value;
      r.gate_arguments.push_back(values);
    }
  if (o.timings_only) r.gate_arguments.push_back("--timings-only");
  r.report_exception = [] { return report_current_exception(); };
  r.option_name = [](std::string_view setting) { return option_name(std::string(setting)); };
  return r;
}

int check(const CheckCliOptions& o) {
  return check_and_report(request_of(o), std::cout);
}

}  // namespace

void add_check_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<CheckCliOptions>();
  auto* cmd = app.add_subcommand(
      "check",
      "Compare a run with a stored baseline (--baseline) or with a base build run beside this one (--against, an "
      "A/B): exit 1 when it got slower or its work changed, 0 with a one-line summary otherwise. A stored baseline "
      "is a result recorded earlier (--update-baseline); the run is a bench of this build, or a result given with "
      "--result. The two modes differ in their defaults: a stored baseline gates on the calibrated frame (the "
      "frame over a calibration probe timed beside it, in probes: 0.45 probes is a frame that took 0.45 times as "
      "long as its probe) with a tolerance of " +
          CheckRequest{}.tolerance + ", an A/B on the " + metric_display_name(AbOptions{}.metrics.front()) + " with " +
          fixed(kAbTolerance * 100, 0) +
          "%. A stored baseline also holds instructions per frame (--count-work): a check slower with the same "
          "count, on a machine seen to have changed, warns (exit 0) instead of failing. See "
          "docs/compare-and-check.md and docs/ci.md.");
  cmd->footer(
      "Examples:\n  crowdprof check scenes/thesis.json --baseline base.json --update-baseline\n"
      "  crowdprof check scenes/thesis.json --baseline base.json\n"
      "  crowdprof check scenes/thesis.json --against ../base-build/crowdprof --junit check.xml");
  options->command = cmd;
  add_bench_options(*cmd, options->bench);
  cmd->get_option("file")->required(false)->description(
      "Character to bench (default: the baseline's scene file); not with --result");
  // A run's options default to what the baseline recorded, not to bench's defaults.
  std::vector<std::string> adopted;
  for (const SettingSpec& setting : setting_table())
    if (setting.name != "bake_rate") adopted.push_back(option_spelling(setting.name));
  for (const SwitchSpec& spec : switch_table()) adopted.push_back(option_spelling(spec.name));
  for (const std::string& name : adopted) {
    CLI::Option* option = cmd->get_option(name);
    std::string text = option->get_description();
    text = text.substr(0, std::min(text.find(" (default:"), text.find(" (overrides the mode's:")));
    option->default_str("")->description(text + " (default: the baseline's)");
  }
  cmd->add_option("--baseline", options->baseline,
                  "Baseline result (bench --json or check --update-baseline); or use --against");
  cmd->add_option("--against", options->against,
                  "A/B instead of a stored baseline: the base build's crowdprof binary, run with the same options in "
                  "ABBA groups of processes beside this build, so that the machine's changes of speed fall on both; "
                  "gates on the paired ratios (Wilcoxon signed-rank); default metric frame, tolerance 5% "
                  "(docs/ci.md)");
  cmd->add_option("--groups", options->groups, "With --against: ABBA groups of four processes (two of each build)")
      ->capture_default_str();
  options->bench.outputs.declare(
      *cmd, OutputOption::Junit, options->junit,
      "Write the verdict as JUnit XML: a test case per metric and one for the work, the verdict as a "
      "failure's message");
  options->bench.outputs.declare(*cmd, OutputOption::Markdown, options->markdown,
                                 "Write the verdict as a Markdown table (a CI job summary or a pull-request comment)");
  cmd->add_option("--result", options->result, "Compare this result of bench --json instead of running a bench");
  cmd->add_option("--metric", options->metrics,
                  "Timed metrics that must not regress: calibrated (the wall-clock frame over a fixed calibration "
                  "probe timed right after it on the same threads, so a change of the machine's speed falls on both; "
                  "its unit is probes: 0.45 probes is a frame that took 0.45 times as long as the probe beside it; "
                  "a baseline or --result without it is checked on cpu; not with --against), cpu (CPU time of every "
                  "thread in the frame, waiting "
                  "workers' spinning included), frame (wall clock), categories such as Animations, Rasterizer, or all: "
                  "the frame and every category "
                  "(Holm-corrected together); or instructions: instructions per frame on one thread (hardware "
                  "counter, else callgrind), tolerance 1%, one run")
      ->delimiter(',')
      ->allow_extra_args(false)  // one comma-separated value: a file after it stays the file
      ->default_str(CheckRequest{}.metrics.front() + "; with --against, " +
                    metric_display_name(AbOptions{}.metrics.front()));
  cmd->add_option("--tolerance", options->tolerance,
                  "Slowdown of the median allowed before a significant shift fails: 7% or 0.07")
      ->default_str(CheckRequest{}.tolerance + "; with --against, " + fixed(kAbTolerance * 100, 0) + "%");
  cmd->add_option("--floor", options->floor,
                  "Smallest slowdown of a median that can fail, however significant: a time (0.05ms, 50us) or a share "
                  "of the baseline's median frame (2%)")
      ->capture_default_str();
  cmd->add_option("--runs,--attempts", options->runs,
                  "Runs to measure, each in a process of its own; with 8 or more here and in the baseline, the gate "
                  "compares the median of each run (processes differ more than frames do), else the frames of the "
                  "median run; --attempts: the older name")
      ->default_str("8; 20 with --update-baseline");
  cmd->add_option("--spread", options->spread,
                  "Seconds the runs are spread over (they wait between them): a machine shared with other jobs is "
                  "slower for seconds at a time, and runs spread out sample several moments (but on some VMs a run "
                  "after an idle wait starts slow: measure first); 0: back to back")
      ->capture_default_str();
  cmd->add_option("--alpha", options->alpha, "Significance level of the Mann-Whitney U test")->capture_default_str();
  cmd->add_option(
         "--confirm", options->confirm,
         "When a timed metric fails and the work is the same, measure again this many times and fail only if "
         "each fails too (a machine shared with other jobs is slow for seconds at a time); 0 to 10, 0: fail at once")
      ->check(CLI::Range(0, 10).description(""))
      ->capture_default_str();
  cmd->add_option("--confirm-spread", options->confirm_spread,
                  "Seconds a confirmation spreads its runs over, so that they sample the machine before, during and "
                  "after a slow spell (at least --spread); 0 to 3600")
      ->check(CLI::Range(0.0, 3600.0).description(""))
      ->capture_default_str();
  cmd->add_option("--count-work", options->count_work,
                  "With --update-baseline of a timed metric: also count the instructions per frame of a few frames "
                  "(hardware counter, else callgrind: about 10 s at 160 copies), so that a later check that runs "
                  "slower with the same count, on a machine seen to have changed (other processes on the cores, the "
                  "probe's own time), warns instead of failing, and one with more instructions fails without "
                  "measuring again")
      ->type_name("on|off")
      ->check(CLI::IsMember({"on", "off"}).description(""))
      ->capture_default_str();
  cmd->add_flag("--timings-only", options->timings_only,
                "Compare timings alone, of runs that may differ (another crowd size): for measuring the gate itself "
                "(tests/scripts/measure_gate.sh); counters and digest are not compared");
  cmd->add_flag("--update-baseline", options->update, "Write the result as the new baseline instead of comparing");
  options->bench.outputs.declare(*cmd, OutputOption::Csv, options->bench.csv,
                                 "Write the run's frames to this CSV file");
  options->bench.outputs.declare(*cmd, OutputOption::Json, options->bench.json,
                                 "Write the run's result (as bench --json) to this file");
  options->bench.outputs.declare(*cmd, OutputOption::Svg, options->svg,
                                 "Write a chart of the metric per frame, baseline against current");
  options->bench.outputs.declare(
      *cmd, OutputOption::Html, options->bench.html,
      "Write an HTML report: the verdict per metric against the tolerance, baseline and current side by side");
  group_outputs(*cmd);
  // Both modes' gate, then each mode's own options.
  group_options(*cmd, kGateGroup, {"--metric", "--tolerance", "--floor", "--alpha", "--timings-only"});
  group_options(*cmd, "Stored baseline",
                {"--baseline", "--update-baseline", "--result", "--runs", "--spread", "--confirm", "--confirm-spread",
                 "--count-work"});
  group_options(*cmd, "A/B of two builds", {"--against", "--groups"});
  cmd->callback([&run, options] { run = [options] { return check(*options); }; });
}

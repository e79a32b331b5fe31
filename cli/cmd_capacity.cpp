// `crowdprof capacity`: per mode, the largest crowd whose median frame (or one
// category) fits a budget, searched over the crowd size in rounds; each round
// runs the modes still searching side by side, interleaved as `compare` runs
// them (frame/capacity.h for the search, cli/compare_modes.h for the runs).
#include <algorithm>
#include <iostream>
#include <memory>

#include "base/errors.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "cli/compare_modes.h"
#include "reports/html_report.h"
#include "base/output_file.h"
#include "frame/run_bench.h"
#include "result/result_codec.h"
#include "frame/capacity.h"
#include "reports/capacity_report.h"
#include "frame/compare.h"
#include "frame/interrupt.h"
#include "gate/regression.h"
#include "reports/summary_csv.h"

using namespace crowdprof;

namespace {

struct CapacityCliOptions {
  BenchCliOptions bench;
  std::string modes;  // comma-separated; empty: every mode the backend can run
  double budget = 0;
  std::string metric = "frame";
  long long start = 10, max_characters = 100'000;
  double resolution = 0.05;
  long long block = 10;
  std::string svg, summary_csv;
};

int capacity(CapacityCliOptions& o) {
  CapacityRule rule;
  rule.budget_ms = o.budget;
  rule.resolution = o.resolution;
  if (o.start < 1 || o.start > 10'000'000)
    throw UsageError("--start " + std::to_string(o.start) + ": expected 1 to 10000000");
  if (o.max_characters < 1 || o.max_characters > 10'000'000)
    throw UsageError("--max-characters " + std::to_string(o.max_characters) + ": expected 1 to 10000000");
  rule.start = static_cast<size_t>(o.start);
  rule.cap = static_cast<size_t>(o.max_characters);
  if (SettingText why = rule.Validate(); !why.empty()) throw SettingsUsageError(why);
  std::optional<CapacityMetric> metric = parse_capacity_metric(o.metric);
  if (!metric)
    throw UsageError("--metric '" + o.metric + "': expected frame or a category (Animations, Rasterizer, ...)");
  check_block(o.block);
  bool named = !o.modes.empty();
  std::vector<std::string> names = modes_to_run(split_commas(o.modes));

  resolve_bench_spec(o.bench);
  require_writable_outputs(o.bench);
  BenchScene scene = load_bench_scene(o.bench.spec);
  std::vector<BenchConfig> configs;
  for (const std::string& name : names) configs.push_back(config_for(o.bench.spec, name, scene));
  configs.front().crowd.copies = rule.start;
  BenchRendering rendering = open_bench_rendering(o.bench, scene, configs.front());
  // Only the modes that can run here; one named that cannot is an error.
  std::vector<ModeCapacity> modes;
  std::vector<BenchConfig> runnable;
  for (BenchConfig& config : configs) {
    config.renderer = rendering.renderer.get();
    SettingText why = why_cannot_run(config);
    if (!why.empty()) {
      if (named) throw SettingsUsageError(why);
      std::cerr << "crowdprof: note: skipping mode " << config.mode_name << ": " << as_options(why) << "\n";
      continue;
    }
    runnable.push_back(config);
  }
  if (runnable.empty()) throw UsageError("none of the modes can run here");
  for (const BenchConfig& config : runnable) {
    ModeCapacity mode;
    mode.mode = config.mode_name;
    mode.rule = rule;
    mode.rule.cap = largest_crowd_in_memory(scene.characters, config, rule.cap, runnable.size());
    if (mode.rule.cap < 1) throw UsageError("mode " + config.mode_name + ": not even one character fits in memory");
    mode.rule.start = std::min(rule.start, mode.rule.cap);
    modes.push_back(mode);
  }

  install_interrupt_handlers();
  size_t rounds = 0;
  CapacityMeasure measure = capacity_measure(scene, runnable, o.bench, static_cast<size_t>(o.block), rendering, rounds);
  CapacityRun result = run_capacity(std::move(modes), *metric, measure);
  result.block = static_cast<size_t>(o.block);
  result.frames = o.bench.spec.frames;
  result.warmup = o.bench.spec.warmup;

  if (o.bench.outputs.files().prints_on_stdout(o.bench.quiet)) std::cout << format_capacity(result);
  if (!o.summary_csv.empty())
    write_text(o.summary_csv, "CSV", [&](std::ostream& out) {
      // Each mode at its capacity: the largest crowd that fit.
      std::vector<const Result*> rows;
      for (const ModeCapacity& mode : result.modes)
        if (mode.fit_run) rows.push_back(&*mode.fit_run);
      write_summary_csv(rows, out);
    });
  if (!o.bench.json.empty())
    write_text(o.bench.json, "JSON", [&](std::ostream& out) {
      out << with_paths_relative_to(capacity_to_json(result), o.bench.json).dump(2) << "\n";
    });
  if (!o.svg.empty()) write_text(o.svg, "SVG", [&](std::ostream& out) { out << capacity_svg(result); });
  if (!o.bench.html.empty()) {
    const bool measured = std::any_of(result.modes.begin(), result.modes.end(),
                                      [](const ModeCapacity& mode) { return mode.fit_run || mode.fail_run; });
    if (!measured) {
      std::cerr << "crowdprof: note: no crowd size was measured whole: no HTML report written to " << o.bench.html
                << "\n";
    } else {
      HtmlReportInput input;
      add_document(input, result_document_from_json(capacity_to_json(result), "this capacity search"),
                   "this capacity search");
      write_html_report(o.bench.html, std::move(input));
    }
  }
  if (result.partial) {
    std::cerr << "crowdprof: interrupted: round " << rounds << " was cut short and is left out of the search; "
              << "the results are those of the " << rounds - 1 << " round" << (rounds == 2 ? "" : "s") << " before it"
              << (o.bench.json.empty() && o.svg.empty() && o.bench.html.empty() && o.summary_csv.empty()
                      ? ""
                      : ", written as a partial result")
              << "\n";
    return kExitInterrupted;
  }
  return kExitOk;
}

}  // namespace

void add_capacity_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<CapacityCliOptions>();
  auto* cmd = app.add_subcommand("capacity",
                                 "Find, per mode, the largest crowd whose median frame (or one category) "
                                 "fits a time budget, by a search over the crowd size");
  cmd->footer("Examples:\n  crowdprof capacity scenes/humanoid.glb --budget 16.7 --modes threaded,shared");
  add_bench_options(*cmd, options->bench);
  cmd->remove_option(cmd->get_option("--mode"));        // --modes instead
  cmd->remove_option(cmd->get_option("--characters"));  // the search picks the sizes
  cmd->add_option("--budget", options->budget, "The budget in ms, e.g. 16.7 (60 fps, as the reports draw it)")
      ->required()
      ->type_name("MS");
  cmd->add_option("--modes", options->modes,
                  "Modes to search (default: every mode the backend can run); a mode may set switches away from its "
                  "preset, e.g. master+lookups=bundled")
      ->type_name("MODE,...");
  cmd->add_option("--metric", options->metric,
                  "What must fit the budget: frame (the median frame time) or a category's median, e.g. Animations")
      ->capture_default_str();
  cmd->add_option("--start", options->start, "The first crowd size tried")->capture_default_str();
  cmd->add_option("--max-characters", options->max_characters,
                  "The largest crowd size tried (lower when the modes' benches would not fit in memory)")
      ->capture_default_str();
  cmd->add_option("--precision", options->resolution,
                  "Stop when the first size over the budget is within this fraction of the largest that fits (or 1 "
                  "character)")
      ->capture_default_str();
  cmd->add_option("--block", options->block, "Frames of one mode before the next mode runs")->capture_default_str();
  options->bench.outputs.declare(
      *cmd, OutputOption::SummaryCsv, options->summary_csv,
      "Write one row per mode at its capacity (the largest crowd that fit) to this CSV file: median, p95, "
      "p99 and fps of the frame and of its CPU time");
  options->bench.outputs.declare(*cmd, OutputOption::Json, options->bench.json,
                                 "Write every size tried per mode, with its median and percentiles");
  options->bench.outputs.declare(*cmd, OutputOption::Svg, options->svg,
                                 "Write a chart: the median against the crowd size per mode, and the budget");
  options->bench.outputs.declare(
      *cmd, OutputOption::Html, options->bench.html,
      "Write an HTML report: each mode's run at its capacity, and the median frame against the crowd size");
  group_outputs(*cmd);
  group_options(*cmd, "Search",
                {"--budget", "--modes", "--metric", "--start", "--max-characters", "--precision", "--block"});
  cmd->callback([&run, options] { run = [options] { return capacity(*options); }; });
}

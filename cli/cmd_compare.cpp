// `crowdprof compare`: the modes side by side on one scene, interleaved in
// blocks of frames, as a table of medians and speedups (the thesis's figures
// 8-11 as numbers), with CSV, JSON, SVG charts, a crowd-size sweep and a trace.
#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "base/output_file.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "base/switch_table.h"
#include "cli/compare_modes.h"
#include "reports/html_report.h"
#include "frame/run_bench.h"
#include "result/result_codec.h"
#include "frame/compare.h"
#include "frame/interrupt.h"
#include "reports/compare_report.h"
#include "gate/regression.h"
#include "reports/gbench_json.h"
#include "reports/summary_csv.h"
#include "measuring/trace.h"

using namespace crowdprof;

namespace {

struct CompareCliOptions {
  BenchCliOptions bench;
  std::string modes;  // comma-separated; empty: every mode the backend can run
  std::string sweep;
  long long block = 10;
  std::string svg, trace, summary_csv, gbench_json;
};

}  // namespace

ModeRun make_benches(const BenchScene& scene, std::vector<BenchConfig> configs, size_t copies, bool named, bool note) {
  ModeRun run;
  std::vector<SettingText> refused;
  for (BenchConfig& config : configs) {
    config.crowd.copies = copies;
    SettingText why = why_cannot_run(config);
    if (why.empty())
      run.configs.push_back(config);
    else if (named)
      throw SettingsUsageError(why);
    else
      refused.push_back(why);
    if (!why.empty() && note)
      std::cerr << "crowdprof: note: skipping mode " << config.mode_name << ": " << as_options(why) << "\n";
  }
  if (run.configs.empty()) {
    // One reason for every mode (a --passes without a GL backend): that reason alone.
    const bool one_reason =
        !refused.empty() && std::all_of(refused.begin(), refused.end(), [&](const SettingText& why) {
          return as_options(why) == as_options(refused.front());
        });
    if (one_reason) throw SettingsUsageError(refused.front());
    // Else the first mode's (master's, in the order modes are listed).
    throw UsageError("none of the modes can run here" +
                     (refused.empty() ? std::string() : " (the first: " + as_options(refused.front()) + ")"));
  }
  check_fits_in_memory(scene.characters, run.configs);  // only the modes that will run
  for (const BenchConfig& config : run.configs)
    run.benches.push_back(std::make_unique<CrowdBench>(scene.characters, config));
  return run;
}

std::vector<Result> run_modes(ModeRun& modes, const BenchCliOptions& o, size_t block, const BenchRendering& rendering,
                              const std::string& what, const std::atomic<bool>* stop) {
  std::vector<CrowdBench*> benches;
  for (auto& bench : modes.benches) benches.push_back(bench.get());
  RunOptions run;
  run.frames = o.spec.frames;
  run.warmup = o.spec.warmup;
  run.progress = terminal_progress(o.quiet, what);
  run.stop = stop ? stop : &interrupt_requested();
  std::vector<Result> reports = run_interleaved(benches, o.spec.file, run, block);
  for (Result& report : reports) {
    report.run.backend = rendering.backend_name();
    report.run.renderer = rendering.renderer_name();
  }
  return reports;
}

CapacityMeasure capacity_measure(const BenchScene& scene, const std::vector<BenchConfig>& configs,
                                 const BenchCliOptions& o, size_t block, const BenchRendering& rendering,
                                 size_t& rounds, const std::atomic<bool>* stop) {
  return [&scene, &configs, &o, block, &rendering, &rounds, stop](std::span<const size_t> active,
                                                                  std::span<const size_t> ns) {
    ModeRun run;
    std::string what = "capacity round " + std::to_string(++rounds) + ":";
    for (size_t k = 0; k < active.size(); ++k) {
      run.configs.push_back(configs[active[k]]);
      run.configs.back().crowd.copies = ns[k];
      what += (k ? ", " : " ") + run.configs.back().mode_name + " n=" + std::to_string(ns[k]);
    }
    check_fits_in_memory(scene.characters, run.configs);
    for (const BenchConfig& config : run.configs)
      run.benches.push_back(std::make_unique<CrowdBench>(scene.characters, config));
    return run_modes(run, o, block, rendering, what + ",", stop);
  };
}

namespace {

int compare(CompareCliOptions& o) {
  check_block(o.block);
  Sweep sweep = o.sweep.empty() ? Sweep{} : parse_sweep(o.sweep);
  bool named = !o.modes.empty();
  std::vector<std::string> names = modes_to_run(split_commas(o.modes));

  resolve_bench_spec(o.bench);
  require_writable_outputs(o.bench);
  BenchScene scene = load_bench_scene(o.bench.spec);
  std::vector<BenchConfig> configs;
  for (const std::string& name : names) configs.push_back(config_for(o.bench.spec, name, scene));
  // One renderer draws every mode in turn: the modes run one block at a time.
  BenchRendering rendering = open_bench_rendering(o.bench, scene, configs.front());
  for (BenchConfig& config : configs) config.renderer = rendering.renderer.get();

  Comparison comparison;
  comparison.block = static_cast<size_t>(o.block);
  comparison.sweep_axis = sweep.axis;
  std::unique_ptr<Tracer> tracer;
  if (!o.trace.empty()) {
    tracer = std::make_unique<Tracer>();
    for (size_t m = 0; m < configs.size(); ++m) {
      configs[m].tracer = tracer.get();
      configs[m].trace_pid = static_cast<int>(m + 1);
    }
  }
  size_t copies = o.bench.spec.characters;
  std::string modes_text = "modes";
  for (const BenchConfig& config : configs) modes_text += (modes_text == "modes" ? " " : ",") + config.mode_name;
  install_interrupt_handlers();
  {
    ModeRun main = make_benches(scene, configs, copies, named, true);
    for (const BenchConfig& config : main.configs)
      if (tracer) tracer->name_process(config.trace_pid, "mode " + config.mode_name);
    comparison.runs = run_modes(main, o.bench, comparison.block, rendering, modes_text + ",");
  }
  for (BenchConfig& config : configs) config.tracer = nullptr;  // the trace shows the main run only
  bool partial = !comparison.runs.empty() && comparison.runs.front().partial;
  const bool by_passes = sweep.axis == SweepAxis::Passes;
  for (size_t n : partial ? std::vector<size_t>{} : sweep.points) {
    bool main_point = by_passes ? std::all_of(configs.begin(), configs.end(),
                                              [&](const BenchConfig& c) { return c.mode.passes == n; })
                                : n == copies;
    if (main_point) {
      comparison.sweep.insert(comparison.sweep.end(), comparison.runs.begin(), comparison.runs.end());
      continue;
    }
    // Passes: every mode as named, drawn n times a frame (its name unchanged, so its line is one).
    std::vector<BenchConfig> at_point = configs;
    for (BenchConfig& config : at_point)
      if (by_passes) config.mode.passes = static_cast<uint32_t>(n);
    ModeRun point = make_benches(scene, at_point, by_passes ? copies : n, named, false);
    std::string label = by_passes ? "sweep passes=" + std::to_string(n) : "sweep n=" + std::to_string(n);
    std::vector<Result> reports =
        run_modes(point, o.bench, comparison.block, rendering, label + ", " + modes_text + ",");
    comparison.sweep.insert(comparison.sweep.end(), reports.begin(), reports.end());
  }

  if (o.bench.outputs.files().prints_on_stdout(o.bench.quiet)) std::cout << format_comparison(comparison);
  if (!o.bench.csv.empty())
    write_text(o.bench.csv, "CSV", [&](std::ostream& out) { write_comparison_csv(comparison, out); });
  // The main run's modes, then the sweep's other points.
  std::vector<const Result*> rows;
  for (const Result& report : comparison.runs) rows.push_back(&report);
  for (const Result& report : comparison.sweep)
    if (!is_main_point(comparison, report)) rows.push_back(&report);
  if (!o.summary_csv.empty())
    write_text(o.summary_csv, "CSV", [&](std::ostream& out) { write_summary_csv(rows, out); });
  if (!o.gbench_json.empty())
    write_text(o.gbench_json, "JSON", [&](std::ostream& out) { out << gbench_document(rows).dump(2) << "\n"; });
  if (!o.bench.json.empty())
    write_text(o.bench.json, "JSON", [&](std::ostream& out) {
      out << with_paths_relative_to(comparison_to_json(comparison), o.bench.json).dump(2) << "\n";
    });
  if (!o.svg.empty()) write_text(o.svg, "SVG", [&](std::ostream& out) { out << comparison_svg(comparison); });
  if (tracer) write_text(o.trace, "trace", [&](std::ostream& out) { tracer->write(out); });
  if (tracer && tracer->dropped())
    std::cerr << "crowdprof: note: " << o.trace << " holds the first " << tracer->max_spans() << " spans; "
              << tracer->dropped() << " later ones were dropped\n";
  if (!o.bench.html.empty()) {
    HtmlReportInput input;
    add_document(input, result_document_from_json(comparison_to_json(comparison), "this comparison"),
                 "this comparison");
    write_html_report(o.bench.html, std::move(input));
  }
  if (partial) {
    bool wrote = !o.bench.csv.empty() || !o.bench.json.empty() || !o.svg.empty() || !o.trace.empty() ||
                 !o.bench.html.empty() || !o.summary_csv.empty() || !o.gbench_json.empty();
    std::cerr << "crowdprof: interrupted: " << comparison.runs.front().frame_records.size() << " of "
              << comparison.runs.front().frames_planned << " frames per mode measured"
              << (wrote ? ", and written as a partial result" : "")
              << (sweep.points.empty() ? "" : "; the sweep was not run") << "\n";
    return kExitInterrupted;
  }
  return kExitOk;
}

}  // namespace

void add_compare_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<CompareCliOptions>();
  auto* cmd = app.add_subcommand("compare",
                                 "Run several modes on one scene, interleaved in blocks of frames, and "
                                 "print each mode's median frame, categories and speedup");
  cmd->footer("Examples:\n  crowdprof compare scenes/humanoid.glb -n 160 --modes master,culled,threaded");
  add_bench_options(*cmd, options->bench);
  cmd->remove_option(cmd->get_option("--mode"));  // --modes instead
  cmd->add_option("--modes", options->modes,
                  "Modes to compare, the first being the reference for speedups (default: every mode the backend "
                  "can run of " +
                      mode_names() +
                      "); a mode may set switches away from its preset, "
                      "e.g. master+lookups=bundled")
      ->type_name("MODE,...");
  cmd->add_option("--block", options->block, "Frames of one mode before the next mode runs")->capture_default_str();
  cmd->add_option("--sweep", options->sweep,
                  "Also run every mode at these crowd sizes, e.g. n=10,20,40,80,160, or drawn this many times a "
                  "frame, e.g. passes=1,2,4,6 (see --passes): rows in the table and JSON, a chart in the SVG and "
                  "HTML");
  options->bench.outputs.declare(*cmd, OutputOption::Csv, options->bench.csv,
                                 "Write one row per measured frame of every mode to this CSV file");
  options->bench.outputs.declare(
      *cmd, OutputOption::SummaryCsv, options->summary_csv,
      "Write one row per mode (and sweep size) to this CSV file: median, p95, p99 and fps of the frame and "
      "of its CPU time");
  options->bench.outputs.declare(*cmd, OutputOption::Json, options->bench.json,
                                 "Write the comparison (and every mode's bench JSON) to this file");
  options->bench.outputs.declare(*cmd, OutputOption::GbenchJson, options->gbench_json,
                                 "Write every mode (and sweep size) as Google Benchmark's JSON, for compare.py, "
                                 "github-action-benchmark or Bencher");
  options->bench.outputs.declare(*cmd, OutputOption::Svg, options->svg,
                                 "Write charts: frame time per frame per mode, categories per mode, cost against drawn "
                                 "error (modes that save work beside what they stray by), sweep");
  options->bench.outputs.declare(
      *cmd, OutputOption::Html, options->bench.html,
      "Write an HTML report: the modes side by side, frame time per frame, categories, the sweep");
  options->bench.outputs.declare(*cmd, OutputOption::Trace, options->trace,
                                 "Write a Chrome trace-event JSON (Perfetto) of the main run");
  group_outputs(*cmd);
  group_options(*cmd, "Comparison", {"--modes", "--block", "--sweep"});
  cmd->callback([&run, options] { run = [options] { return compare(*options); }; });
}

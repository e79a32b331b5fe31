// `crowdprof bench`: the main job. Parses options into a BenchConfig, runs the
// frames and prints the profile; the work itself is in lib/frame.
#include <iostream>
#include <memory>
#include <thread>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "reports/html_report.h"
#include "base/output_file.h"
#include "frame/run_bench.h"
#include "result/result_codec.h"
#include "frame/interrupt.h"
#include "gate/regression.h"
#include "reports/gbench_json.h"
#include "reports/summary_csv.h"
#include "measuring/instruction_counter.h"
#include "measuring/trace.h"
#include "render/gl_errors.h"
#include "render/png.h"

namespace {

using namespace crowdprof;

// Outputs bench has and the other commands' shared options do not.
struct BenchOutputs {
  std::string summary_csv, gbench_json, scene_out;
  bool count_instructions = false;
  bool calibrate = false;
};

int bench(BenchCliOptions& options, const BenchOutputs& outputs) {
  const std::string& summary_csv = outputs.summary_csv;
  const std::string& gbench_json = outputs.gbench_json;
  resolve_bench_spec(options);
  const RunSpec& spec = options.spec;
  validate_run_spec(spec);
  require_writable_outputs(options);
  BenchScene scene = load_bench_scene(spec);
  BenchConfig config = make_bench_config(spec, scene);
  check_fits_in_memory(scene.characters, config);
  // Instructions are counted on the frame's thread: workers' would be missed.
  if (outputs.count_instructions && config.mode.parallel && config.threads != 1)
    throw UsageError("--count-instructions counts the frame's own thread: with mode " + config.mode_name +
                     " (parallel), add --threads 1");
  // The report embeds the screenshot by reading it back: it needs a file.
  if (is_standard_output(options.screenshot) && !options.html.empty())
    throw UsageError("--screenshot " + options.screenshot +
                     " with --html: the report reads the screenshot back from "
                     "its file; give --screenshot a file");
  if (!options.screenshot.empty() && spec.backend == "none")
    throw UsageError("--screenshot needs a GL backend: --backend auto, egl or osmesa");
  BenchRendering rendering = open_bench_rendering(options, scene, config);
  if (!options.screenshot.empty() && !rendering.renderer)
    throw GlUnavailable("--screenshot: no GL backend could be opened, so no frame would be drawn");
  std::unique_ptr<Tracer> tracer;
  if (!options.trace.empty()) {
    tracer = std::make_unique<Tracer>();
    tracer->name_process(1, "mode " + config.mode_name);
    config.tracer = tracer.get();
    // Said before a long run, not after it.
    SettingText warning = trace_length_warning(spec.frames + spec.warmup, tracer->max_spans());
    if (!warning.empty()) std::cerr << "crowdprof: warning: " << as_options(warning) << "\n";
  }
  CrowdBench crowd(scene.characters, config);
  RunOptions run;
  run.frames = spec.frames;
  run.warmup = spec.warmup;
  run.progress = terminal_progress(options.quiet, "mode " + config.mode_name + ",");
  install_interrupt_handlers();
  run.stop = &interrupt_requested();
  run.count_instructions = outputs.count_instructions;
  run.calibrate = outputs.calibrate;
  Result report = run_bench(crowd, spec.file, run);
  report.run.backend = rendering.backend_name();
  report.run.renderer = rendering.renderer_name();
  if (options.outputs.files().prints_on_stdout(options.quiet)) std::cout << format_profile(report);
  if (!options.csv.empty()) write_text(options.csv, "CSV", [&](std::ostream& out) { write_csv(report, out); });
  if (!summary_csv.empty())
    write_text(summary_csv, "CSV", [&](std::ostream& out) { write_summary_csv({&report}, out); });
  if (!gbench_json.empty())
    write_text(gbench_json, "JSON", [&](std::ostream& out) { out << gbench_document({&report}).dump(2) << "\n"; });
  if (!options.json.empty()) write_result_file(options.json, "JSON", report);
  if (tracer) write_text(options.trace, "trace", [&](std::ostream& out) { tracer->write(out); });
  if (tracer && tracer->dropped())
    std::cerr << "crowdprof: note: " << options.trace << " holds the first " << tracer->max_spans() << " spans; "
              << tracer->dropped() << " later ones were dropped\n";
  if (report.partial) {
    bool wrote = !options.csv.empty() || !options.json.empty() || !options.trace.empty() || !summary_csv.empty() ||
                 !gbench_json.empty();
    std::cerr << "crowdprof: interrupted: " << report.frames() << " of " << report.frames_planned << " frames measured"
              << (wrote ? ", and written as a partial result" : "") << "\n";
    if (!outputs.scene_out.empty())
      std::cerr << "crowdprof: note: --scene-out " << outputs.scene_out << " is not written from a cut run\n";
    return kExitInterrupted;
  }
  if (!options.screenshot.empty()) {
    std::vector<uint8_t> pixels = rendering.renderer->read_pixels();
    write_png(options.screenshot, rendering.renderer->width(), rendering.renderer->height(), pixels);
  }
  if (!outputs.scene_out.empty()) write_scene_out(outputs.scene_out, spec, scene, config);
  if (!options.html.empty()) {
    HtmlReportInput input;
    add_result(input, report, "this run");
    if (!options.screenshot.empty()) input.screenshot_png = read_png(options.screenshot);
    write_html_report(options.html, std::move(input));
  }
  return kExitOk;
}

}  // namespace

void add_bench_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<BenchCliOptions>();
  auto outputs = std::make_shared<BenchOutputs>();
  auto* cmd = app.add_subcommand("bench",
                                 "Fill a scene with copies of a character (or the crowd of a scene file), "
                                 "play actions and print where each frame's time goes (BGE-style profile)");
  cmd->footer("Examples:\n  crowdprof bench scenes/thesis.json --mode culled --json result.json");
  add_bench_options(*cmd, *options);
  options->outputs.declare(*cmd, OutputOption::Csv, options->csv, "Write one row per measured frame to this CSV file");
  options->outputs.declare(
      *cmd, OutputOption::GbenchJson, outputs->gbench_json,
      "Write the run as Google Benchmark's JSON (each frame a repetition; mean, median, stddev), for "
      "compare.py, github-action-benchmark or Bencher");
  cmd->add_flag("--count-instructions", outputs->count_instructions, kCountInstructionsHelp);
  cmd->add_flag("--calibrate", outputs->calibrate,
                "After every frame, time a fixed calibration probe (a skinning kernel of fixed size on the same "
                "threads) and record each frame over it: the metric check --metric calibrated compares, which a "
                "change of the machine's speed moves less than the frame; in --json as samples.probe_ms and "
                "samples.calibrated");
  options->outputs.declare(
      *cmd, OutputOption::SummaryCsv, outputs->summary_csv,
      "Write one row for the run to this CSV file: median, p95, p99 and fps of the frame and of its CPU time");
  options->outputs.declare(*cmd, OutputOption::Json, options->json,
                           "Write the run's summary (and per-frame samples) to this JSON file");
  options->outputs.declare(
      *cmd, OutputOption::Trace, options->trace,
      "Write a Chrome trace-event JSON (Perfetto, chrome://tracing): a span per stage per frame, and per "
      "task on each worker thread");
  options->outputs.declare(*cmd, OutputOption::Screenshot, options->screenshot,
                           "Write the last frame as a PNG (needs a GL backend)");
  options->outputs.declare(
      *cmd, OutputOption::SceneOut, outputs->scene_out,
      "Write the run's configuration (crowd, camera, resolution, mode, switches, threads) as a scene file that "
      "bench runs as is (docs/scenes.md); not written when the run is cut short");
  options->outputs.declare(
      *cmd, OutputOption::Html, options->html,
      "Write an HTML report of the run (charts, the profile, environment, the screenshot): one file that "
      "opens in any browser");
  group_outputs(*cmd);
  // What each frame records besides its time: choices of measurement, not files.
  group_options(*cmd, kMeasurementGroup, {"--frames", "--warmup", "--calibrate", "--count-instructions"});
  cmd->callback([&run, options, outputs] { run = [options, outputs] { return bench(*options, *outputs); }; });
}

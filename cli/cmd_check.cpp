// `crowdprof check`: runs a bench (or reads a result of bench --json) and
// compares it with a baseline: exit 1 when a metric regressed beyond the
// tolerance and significantly, or when the work done (counters, digest)
// changed; exit 0 with a one-line summary otherwise. The logic is in
// lib/profile/regression.h.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <tuple>

#include "asset/errors.h"
#include "asset/gltf_loader.h"
#include "output/output_file.h"
#include "cli/bench_options.h"
#include "cli/child_run.h"
#include "cli/commands.h"
#include "cli/html_output.h"
#include "cli/output.h"
#include "frame/interrupt.h"
#include "frame/run_bench.h"
#include "profile/regression.h"
#include "profile/report_charts.h"
#include "profile/svg_chart.h"

namespace {

using namespace crowdprof;
using nlohmann::json;

struct CheckCliOptions {
  BenchCliOptions bench;
  std::string baseline, result;
  std::vector<std::string> metrics = {"cpu"};
  std::string tolerance = "7%";
  std::string floor = "2%";
  // A baseline is held against every later check, so its luck counts many
  // times: it gets more runs than a check (docs/compare-and-check.md).
  long long runs = 8, baseline_runs = 20;
  // Runs spread over this many seconds sample several moments of a machine
  // shared with other jobs. Not by default: on the development VM a run that
  // starts after an idle wait is often 20-45% slower (docs/compare-and-check.md).
  double spread = 0, baseline_spread = 0;
  double alpha = 0.05;
  bool update = false;
  bool timings_only = false;
  std::string svg;
  CLI::App* command = nullptr;  // to tell options given from defaults
  bool action_from_baseline = false;
  bool file_from_baseline = false;  // the scene file is the one the baseline recorded
};

bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  return !a.empty() && (a == b || std::filesystem::equivalent(a, b, error));
}

// A switch as its option takes it: strings as they are, booleans as on/off.
std::string switch_value(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "on" : "off";
  return value.dump();
}

std::string optional_text(const json& section, const char* key) {
  return section.is_object() && section.contains(key) && section[key].is_string() ? section[key].get<std::string>() : "";
}

// The bench options that recorded `baseline` (validated: types are by read_result).
BenchCliOptions options_recorded_in(const json& baseline) {
  const json& scene = baseline["scene"];
  const json& switches = baseline["switches"];
  BenchCliOptions r;
  r.file = scene["file"].get<std::string>();
  r.characters = scene["characters"].get<long long>();
  r.frames = baseline["frames"].get<long long>();
  r.warmup = baseline["warmup"].get<long long>();
  r.fps = baseline["fps"].get<double>();
  r.actions = scene["action_choice"].get<std::string>();
  r.action = optional_text(scene, "action");
  r.seed = scene["seed"].get<long long>();
  r.camera = scene["camera"].get<std::string>();
  if (std::string resolution = optional_text(scene, "resolution"); !resolution.empty()) r.resolution = resolution;
  r.mode = baseline["mode"].get<std::string>();
  if (r.mode.ends_with("+custom")) r.mode.resize(r.mode.size() - 7);
  for (auto [key, value] : {std::pair<const char*, std::string*>{"lookups", &r.lookups}, {"culling", &r.culling},
                            {"pose", &r.pose}, {"parallel", &r.parallel}, {"skinning", &r.skinning},
                            {"vertex_format", &r.vertex_format},
                            {"palettes", &r.palettes}, {"draw", &r.draw},
                            {"share", &r.share}, {"share_quantum", &r.share_quantum}, {"update_lod", &r.update_lod},
                            {"lod_thresholds", &r.lod_thresholds}, {"anim_budget", &r.anim_budget}})
    if (switches.contains(key)) *value = switch_value(switches[key]);
  if (r.parallel == "on") r.threads = baseline["threads"].get<long long>();
  if (std::string backend = optional_text(baseline["environment"], "backend"); !backend.empty()) r.backend = backend;
  r.allow_static = scene["actions"].get<long long>() == 0;
  if (scene.contains("lens") && scene["lens"].is_object() && scene["lens"].contains("focal_mm") &&
      scene["lens"]["focal_mm"].is_number())
    r.lens = scene["lens"]["focal_mm"].get<double>();
  return r;
}

// Options left at their defaults take the baseline's values, so that
// `check --baseline B` reruns what B recorded. A value no run could have
// recorded is the baseline's fault, not the command line's: InputError.
void adopt_baseline_options(CheckCliOptions& o, const json& baseline) {
  BenchCliOptions recorded = options_recorded_in(baseline);
  try {
    validate_bench_options(recorded);
  } catch (const UsageError& e) {
    throw InputError(o.baseline, std::string("records a run that crowdprof cannot make: ") + e.what());
  }
  auto given = [&](const char* name) { return o.command->count(name) > 0; };
  BenchCliOptions& b = o.bench;
  if (b.file.empty()) {
    b.file = recorded_scene_file(baseline, o.baseline);
    o.file_from_baseline = true;
  }
  if (!given("--characters")) b.characters = recorded.characters;
  if (!given("--frames")) b.frames = recorded.frames;
  if (!given("--warmup")) b.warmup = recorded.warmup;
  if (!given("--fps")) b.fps = recorded.fps;
  if (!given("--actions")) b.actions = recorded.actions;
  if (!given("--seed")) b.seed = recorded.seed;
  if (!given("--camera")) b.camera = recorded.camera;
  if (!given("--resolution")) b.resolution = recorded.resolution;
  if (!given("--backend")) b.backend = recorded.backend;
  if (!given("--static")) b.allow_static = recorded.allow_static;
  if (!given("--lens") && recorded.lens != 0) b.lens = recorded.lens;
  // What a scene file would set counts as given: the rerun is the baseline's
  // run, overrides included, whatever the scene file says now.
  for (const char* name : {"--characters", "--actions", "--seed", "--camera", "--resolution", "--lens"})
    if (!given(name)) b.adopted.insert(name);
  if (!given("--action") && b.actions == "shared" && !recorded.action.empty()) {
    b.action = recorded.action;
    b.adopted.insert("--action");
    o.action_from_baseline = true;
  }
  // A mode given on the command line brings its own switches; else the
  // baseline's mode with its switches as recorded.
  if (!given("--mode")) {
    b.mode = recorded.mode;
    for (auto [option, mine, theirs] : {std::tuple{"--lookups", &b.lookups, &recorded.lookups},
                                        {"--culling", &b.culling, &recorded.culling},
                                        {"--pose", &b.pose, &recorded.pose},
                                        {"--parallel", &b.parallel, &recorded.parallel},
                                        {"--skinning", &b.skinning, &recorded.skinning},
                                        {"--vertex-format", &b.vertex_format, &recorded.vertex_format}})
      if (!given(option)) *mine = *theirs;
  }
  const ModePreset* preset = find_mode(b.mode);
  bool parallel = b.parallel.empty() ? preset && preset->switches.parallel : b.parallel == "on";
  if (!given("--threads") && parallel && recorded.threads != kThreadsUnset) b.threads = recorded.threads;
}

// The baseline named an action this character does not have: the baseline
// is of another character, which is a bad baseline rather than a bad option.
void require_recorded_action(const CheckCliOptions& o, const Character& character) {
  if (!o.action_from_baseline) return;
  std::string names;
  for (const Action& action : character.actions) {
    if (action.name == o.bench.action) return;
    names += (names.empty() ? "" : ", ") + action.name;
  }
  throw InputError(o.baseline, "the baseline is of another run: its action '" + o.bench.action + "' is not one of " +
                                   o.bench.file + "'s (" + names + ")");
}

RunReport run_bench_report(CheckCliOptions& o, const std::string& progress_label) {
  BenchScene scene;
  try {
    scene = load_bench_scene(o.bench);
  } catch (const InputError& e) {
    if (!o.file_from_baseline) throw;
    throw InputError(o.baseline, std::string("its scene file: ") + e.what() +
                                     " (the path the baseline recorded, resolved from the baseline's folder)");
  }
  require_recorded_action(o, scene.first());
  BenchConfig config = make_bench_config(o.bench, scene);
  check_fits_in_memory(scene.characters, config);
  BenchRendering rendering = open_bench_rendering(o.bench, scene, config);
  CrowdBench bench(scene.characters, config);
  RunOptions run;
  run.frames = static_cast<size_t>(o.bench.frames);
  run.warmup = static_cast<size_t>(o.bench.warmup);
  run.progress = terminal_progress(o.bench.quiet, progress_label + ", mode " + config.mode_name + ",");
  install_interrupt_handlers();
  run.stop = &interrupt_requested();
  RunReport report = run_bench(bench, o.bench.file, run);
  report.run.backend = rendering.backend_name();
  report.run.renderer = rendering.renderer_name();
  return report;
}

void write_svg(const std::string& path, const json& baseline, const json& current, const std::string& metric) {
  std::string shown = metric == "frame_ms" ? "frame" : metric == "cpu_ms" ? "CPU" : metric;
  LineChart chart{"check: " + shown + " time per frame, baseline and current: " + scene_caption(current),
                  "frame (0 = the first measured, after " + std::to_string(current["warmup"].get<size_t>()) + " warm-up)",
                  "time (ms)", {}, false};
  ModeColours colours(preset_mode_order());  // baseline and current as the HTML report colours them
  for (const auto& [name, doc] : {std::pair<const char*, const json*>{"baseline", &baseline}, {"current", &current}}) {
    LineSeries series{name, {}, doc->at("samples").at(metric).get<std::vector<double>>(), colours.colour(name)};
    for (size_t i = 0; i < series.y.size(); ++i) series.x.push_back(static_cast<double>(i));
    chart.series.push_back(std::move(series));
  }
  SvgDocument svg;
  svg.add(chart);
  write_text(path, "SVG", [&](std::ostream& out) { out << svg.str(); });
}

int check(CheckCliOptions& o) {
  CheckOptions options;
  options.tolerance = parse_tolerance(o.tolerance);
  options.floor = parse_floor(o.floor);
  if (!(o.alpha > 0 && o.alpha < 1)) throw UsageError("--alpha " + std::to_string(o.alpha) + ": expected between 0 and 1");
  if (o.update && o.command->count("--runs") == 0) o.runs = o.baseline_runs;
  if (o.update && o.command->count("--spread") == 0) o.spread = o.baseline_spread;
  if (!(o.spread >= 0 && o.spread <= 3600))
    throw UsageError("--spread " + std::to_string(o.spread) + ": expected 0 to 3600 seconds");
  if (o.runs < 1 || o.runs > static_cast<long long>(kMaxRuns))
    throw UsageError("--runs " + std::to_string(o.runs) + ": expected 1 to " + std::to_string(kMaxRuns));
  options.alpha = o.alpha;
  options.compare_work = !o.timings_only;
  if (o.timings_only && o.update) throw UsageError("--timings-only compares; it cannot record a baseline");
  options.metrics.clear();
  for (const std::string& metric : o.metrics) {
    if (metric == "all") {
      for (const std::string& key : all_metrics())
        if (std::find(options.metrics.begin(), options.metrics.end(), key) == options.metrics.end())
          options.metrics.push_back(key);
      continue;
    }
    std::string key = resolve_metric(metric);
    if (std::find(options.metrics.begin(), options.metrics.end(), key) == options.metrics.end())
      options.metrics.push_back(key);
  }
  if (!o.result.empty() && !o.bench.file.empty())
    throw UsageError("give either a scene FILE to run or --result FILE to read, not both");

  // Outputs are checked before a run that would be lost, and a comparison never
  // overwrites what it compares against.
  if (!o.update && same_file(o.bench.json, o.baseline))
    throw UsageError("--json " + o.bench.json + " is the baseline; to replace it, use --update-baseline");
  auto require_safe_outputs = [&] {
    std::vector<NamedPath> inputs = {{"--result file", o.result}};
    if (!o.update) inputs.push_back({"baseline", o.baseline});
    std::vector<NamedPath> outputs = {{"--svg", o.svg}};  // --html is among the bench options
    if (o.update) outputs.push_back({"--baseline", o.baseline});
    require_writable_outputs(o.bench, inputs, outputs);
  };
  require_safe_outputs();
  if (!o.svg.empty()) require_writable(o.svg, "SVG");
  if (o.update) require_writable(o.baseline, "baseline");
  // A bad baseline is found before a long run, not after it. One being
  // replaced only lends its options, if it can.
  std::optional<json> baseline;
  if (!o.update) {
    if (!std::filesystem::exists(o.baseline))
      throw InputError(o.baseline, "no such file (record a baseline first with --update-baseline)");
    baseline = read_result(o.baseline);
  } else if (o.result.empty() && std::filesystem::exists(o.baseline)) {
    try {
      baseline = read_result(o.baseline);
    } catch (const InputError& e) {
      std::cerr << "crowdprof: note: replacing a baseline that cannot be read (" << e.what() << ")\n";
    }
  }
  // Each run is a process of its own (child_run.h): the CPU time of one
  // unchanged scene moves about three times more between processes than within
  // one, so a baseline and a check each sample --runs processes, and the gate
  // compares their medians. The CSV is of the last run.
  json current;
  if (!o.result.empty()) {
    current = read_result(o.result);
  } else {
    if (baseline) adopt_baseline_options(o, *baseline);
    if (o.bench.file.empty()) throw UsageError("check needs a scene FILE to run, or --result FILE");
    require_safe_outputs();  // the scene file may have come from the baseline
    std::vector<json> runs;
    bool interrupted = false;
    install_interrupt_handlers();  // here, to forward a ^C to the run in progress
    auto start = std::chrono::steady_clock::now();
    for (long long i = 1; i <= o.runs && !interrupted; ++i) {
      // Run i starts (i - 1) / (runs - 1) of the way through the spread.
      if (i > 1 && o.spread > 0) {
        auto due = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                               std::chrono::duration<double>(o.spread * static_cast<double>(i - 1) /
                                                             static_cast<double>(o.runs - 1)));
        while (std::chrono::steady_clock::now() < due && !interrupt_requested().load())
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
        if (interrupt_requested().load()) {
          interrupted = true;
          break;
        }
      }
      std::string label = o.runs > 1 ? "check, run " + std::to_string(i) + " of " + std::to_string(o.runs) : "check";
      auto run_started = i == 1 ? start : std::chrono::steady_clock::now();
      json run = run_in_child_process([&] {
        RunReport report = run_bench_report(o, label);
        if (!o.bench.csv.empty()) write_text(o.bench.csv, "CSV", [&](std::ostream& out) { write_csv(report, out); });
        json j = to_json(report);
        j["pid"] = static_cast<long long>(::getpid());
        return j;
      });
      run["started_s"] = std::chrono::duration<double>(run_started - start).count();
      interrupted = run.value("partial", false) || interrupt_requested().load();
      if (run.value("partial", false)) {
        run.erase("pid");
        run.erase("started_s");
        current = std::move(run);
      } else {
        // Another run than the baseline's is found after one run, not after all.
        if (runs.empty() && baseline && !o.update && !o.timings_only) require_same_run(*baseline, run, o.baseline);
        runs.push_back(std::move(run));
      }
    }
    if (interrupted) {
      // The frames measured so far: the cut run's, or the last whole one's.
      if (current.is_null() && !runs.empty()) current = std::move(runs.back());
      if (current.is_object()) {
        current.erase("pid");
        current.erase("started_s");
        current["partial"] = true;
        if (!o.bench.json.empty())
          write_text(o.bench.json, "JSON", [&](std::ostream& out) { out << current.dump(2) << "\n"; });
      }
      std::cerr << "crowdprof: interrupted: "
                << (o.update ? "the baseline is not updated from a partial run" : "a partial run is not compared") << "\n";
      return kExitInterrupted;
    }
    current = pooled_runs(std::move(runs), options.metrics.front());
  }

  if (o.update) {
    if (!o.bench.json.empty())
      write_text(o.bench.json, "JSON",
                 [&](std::ostream& out) { out << with_paths_relative_to(current, o.bench.json).dump(2) << "\n"; });
    write_text(o.baseline, "baseline",
               [&](std::ostream& out) { out << with_paths_relative_to(current, o.baseline).dump(2) << "\n"; });
    if (!o.bench.html.empty()) {
      HtmlReportInput input;
      add_result_document(input, current, o.baseline);
      write_html_report(o.bench.html, std::move(input));
    }
    if (!o.bench.quiet)
      std::cout << "baseline written: " << o.baseline << " (" << current["mode"].get<std::string>() << ", "
                << current["scene"]["characters"] << " characters, frame median "
                << current["frame"]["median_ms"].get<double>() << " ms"
                << (o.result.empty() && o.runs > 1 ? ", the median of " + std::to_string(o.runs) + " runs by " + metric_display_name(options.metrics.front()) : "")
                << ", digest " << current["digest"].get<std::string>() << ")\n";
    return kExitOk;
  }
  // A baseline from before CPU time was recorded is checked on the frame, when
  // the metric was not asked for by name.
  if (o.command->count("--metric") == 0 && !baseline->at("samples").contains("cpu_ms")) {
    std::cerr << "crowdprof: note: " << o.baseline
              << " has no CPU time per frame (an older crowdprof's): checking the frame time instead\n";
    options.metrics = {"frame_ms"};
  }
  if (!o.timings_only) require_same_run(*baseline, current, o.baseline);
  for (const std::string& note : comparison_notes(*baseline, current))
    std::cerr << "crowdprof: " << (note.rfind("warning: ", 0) == 0 ? "" : "note: ") << note << "\n";
  for (const std::string& key : options.metrics)
    for (const auto& [doc, path] : {std::pair{&*baseline, o.baseline}, {&current, o.result.empty() ? std::string("the run") : o.result}})
      if (!doc->at("samples").contains(key))
        throw InputError(path, "has no \"samples." + key + "\" (recorded by an older crowdprof): record it again, or "
                               "check another --metric");
  CheckResult result = check_results(*baseline, current, options);
  if (!o.bench.json.empty())
    write_text(o.bench.json, "JSON",
               [&](std::ostream& out) { out << with_paths_relative_to(current, o.bench.json).dump(2) << "\n"; });
  if (!o.svg.empty()) write_svg(o.svg, *baseline, current, options.metrics.front());
  if (!o.bench.html.empty()) {
    // Both runs side by side under the verdict.
    HtmlReportInput input;
    add_result_document(input, *baseline, o.baseline);
    add_result_document(input, current, o.result.empty() ? "this run" : o.result);
    input.runs[0].label = "baseline";
    input.runs[1].label = "current";
    input.check = CheckSection{result, options, o.baseline};
    write_html_report(o.bench.html, std::move(input));
  }
  if (!o.bench.quiet) std::cout << format_check(result, options);
  return result.regressed() ? kExitRegression : kExitOk;
}

}  // namespace

void add_check_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<CheckCliOptions>();
  auto* cmd = app.add_subcommand("check", "Run a bench (or read a result) and compare it with a baseline: exit 1 "
                                          "when it got slower or its work changed (see docs/compare-and-check.md)");
  cmd->footer(
      "Examples:\n  crowdprof check scenes/thesis.json --baseline base.json --update-baseline\n"
      "  crowdprof check scenes/thesis.json --baseline base.json");
  options->command = cmd;
  add_bench_options(*cmd, options->bench);
  cmd->get_option("file")->required(false)->description(
      "Character to bench (default: the baseline's scene file); not with --result");
  // A run's options default to what the baseline recorded, not to bench's defaults.
  for (const char* name : {"--characters", "--actions", "--action", "--seed", "--frames", "--warmup", "--fps", "--mode",
                           "--threads", "--camera", "--lens", "--backend", "--resolution", "--lookups", "--culling",
                           "--pose", "--parallel", "--skinning", "--vertex-format", "--static"}) {
    CLI::Option* option = cmd->get_option(name);
    std::string text = option->get_description();
    text = text.substr(0, text.find(" (default:"));
    option->default_str("")->description(text + " (default: the baseline's)");
  }
  cmd->add_option("--baseline", options->baseline, "Baseline result (bench --json or check --update-baseline)")
      ->required();
  cmd->add_option("--result", options->result, "Compare this result of bench --json instead of running a bench");
  cmd->add_option("--metric", options->metrics,
                  "Timed metrics that must not regress: cpu (CPU time of every thread in the frame), frame (wall "
                  "clock), categories such as Animations, Rasterizer, or all: the frame and every category "
                  "(Holm-corrected together)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--tolerance", options->tolerance,
                  "Slowdown of the median allowed before a significant shift fails: 7% or 0.07")
      ->capture_default_str();
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
  cmd->add_flag("--timings-only", options->timings_only,
                "Compare timings alone, of runs that may differ (another crowd size): for measuring the gate itself "
                "(tests/scripts/measure_gate.sh); counters and digest are not compared");
  cmd->add_flag("--update-baseline", options->update, "Write the result as the new baseline instead of comparing");
  cmd->add_option("--csv", options->bench.csv, "Write the run's frames to this CSV file");
  cmd->add_option("--json", options->bench.json, "Write the run's result (as bench --json) to this file");
  cmd->add_option("--svg", options->svg, "Write a chart of the metric per frame, baseline against current");
  cmd->add_option("--html", options->bench.html,
                  "Write an HTML report: the verdict per metric against the tolerance, baseline and current side by side");
  cmd->callback([&run, options] { run = [options] { return check(*options); }; });
}

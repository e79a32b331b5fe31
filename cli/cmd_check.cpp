// `crowdprof check`: runs a bench (or reads a result of bench --json) and
// compares it with a baseline: exit 1 when a metric regressed beyond the
// tolerance and significantly, or when the work done (counters, digest)
// changed; exit 0 with a one-line summary otherwise. The logic is in
// lib/profile/regression.h.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "asset/errors.h"
#include "asset/gltf_loader.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "cli/output.h"
#include "frame/run_bench.h"
#include "profile/regression.h"
#include "profile/svg_chart.h"

namespace {

using namespace crowdprof;
using nlohmann::json;

struct CheckCliOptions {
  BenchCliOptions bench;
  std::string baseline, result;
  std::vector<std::string> metrics = {"frame"};
  std::string tolerance = "10%";
  double alpha = 0.05;
  bool update = false;
  std::string svg;
  CLI::App* command = nullptr;  // to tell options given from defaults
};

// Options left at their defaults take the baseline's values, so that
// `check FILE --baseline B` reruns what B recorded.
void adopt_baseline_options(CheckCliOptions& o, const json& baseline) {
  auto given = [&](const char* name) { return o.command->count(name) > 0; };
  const json& scene = baseline["scene"];
  if (o.bench.file.empty()) o.bench.file = scene["file"].get<std::string>();
  if (!given("--characters")) o.bench.characters = scene["characters"].get<long long>();
  if (!given("--frames")) o.bench.frames = baseline["frames"].get<long long>();
  if (!given("--warmup")) o.bench.warmup = baseline["warmup"].get<long long>();
  if (!given("--fps")) o.bench.fps = baseline["fps"].get<double>();
  if (!given("--actions")) o.bench.actions = scene["action_choice"].get<std::string>();
  if (!given("--seed")) o.bench.seed = scene["seed"].get<long long>();
  if (!given("--camera")) o.bench.camera = scene["camera"].get<std::string>();
  std::string mode = baseline["mode"].get<std::string>();
  if (!given("--mode") && find_mode(mode)) o.bench.mode = mode;
  const ModePreset* preset = find_mode(o.bench.mode);
  if (!given("--threads") && preset && preset->switches.parallel) o.bench.threads = baseline["threads"].get<long long>();
  if (!given("--backend") && baseline.contains("environment") && baseline["environment"].is_object() &&
      baseline["environment"].value("backend", json("none")).is_string())
    o.bench.backend = baseline["environment"].value("backend", json("none")).get<std::string>();
}

json run_bench_result(const CheckCliOptions& o) {
  Character character = load_character(o.bench.file);
  BenchConfig config = make_bench_config(o.bench, character);
  check_fits_in_memory(character, config.crowd.copies, config.mode);
  BenchRendering rendering = open_bench_rendering(o.bench, character, config);
  CrowdBench bench(character, config);
  RunOptions run;
  run.frames = static_cast<size_t>(o.bench.frames);
  run.warmup = static_cast<size_t>(o.bench.warmup);
  run.progress = terminal_progress(o.bench.quiet);
  RunReport report = run_bench(bench, o.bench.file, run);
  report.run.backend = rendering.backend_name();
  report.run.renderer = rendering.renderer_name();
  if (!o.bench.csv.empty()) write_text(o.bench.csv, "CSV", [&](std::ostream& out) { write_csv(report, out); });
  return to_json(report);
}

void write_svg(const std::string& path, const json& baseline, const json& current, const std::string& metric) {
  LineChart chart{"check: " + (metric == "frame_ms" ? std::string("frame") : metric) + " time per frame, baseline and current",
                  "frame (after warm-up)", "time (ms)", {}, false};
  for (const auto& [name, doc] : {std::pair<const char*, const json*>{"baseline", &baseline}, {"current", &current}}) {
    LineSeries series{name, {}, doc->at("samples").at(metric).get<std::vector<double>>()};
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
  if (!(o.alpha > 0 && o.alpha < 1)) throw UsageError("--alpha " + std::to_string(o.alpha) + ": expected between 0 and 1");
  options.alpha = o.alpha;
  options.metrics.clear();
  for (const std::string& metric : o.metrics) options.metrics.push_back(resolve_metric(metric));
  if (!o.result.empty() && !o.bench.file.empty())
    throw UsageError("give either a scene FILE to run or --result FILE to read, not both");

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
  json current;
  if (!o.result.empty()) {
    current = read_result(o.result);
  } else {
    if (baseline) adopt_baseline_options(o, *baseline);
    if (o.bench.file.empty()) throw UsageError("check needs a scene FILE to run, or --result FILE");
    current = run_bench_result(o);
  }
  if (!o.bench.json.empty())
    write_text(o.bench.json, "JSON", [&](std::ostream& out) { out << current.dump(2) << "\n"; });

  if (o.update) {
    write_text(o.baseline, "baseline", [&](std::ostream& out) { out << current.dump(2) << "\n"; });
    if (!o.bench.quiet)
      std::cout << "baseline written: " << o.baseline << " (" << current["mode"].get<std::string>() << ", "
                << current["scene"]["characters"] << " characters, frame median "
                << current["frame"]["median_ms"].get<double>() << " ms, digest " << current["digest"].get<std::string>()
                << ")\n";
    return kExitOk;
  }
  require_same_run(*baseline, current, o.baseline);
  for (const std::string& note : comparison_notes(*baseline, current)) std::cerr << "crowdprof: note: " << note << "\n";
  CheckResult result = check_results(*baseline, current, options);
  if (!o.svg.empty()) write_svg(o.svg, *baseline, current, options.metrics.front());
  if (!o.bench.quiet) std::cout << format_check(result, options);
  return result.regressed() ? kExitRegression : kExitOk;
}

}  // namespace

void add_check_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<CheckCliOptions>();
  auto* cmd = app.add_subcommand("check", "Run a bench (or read a result) and compare it with a baseline: exit 1 "
                                          "when it got slower or its work changed (see docs/compare-and-check.md)");
  options->command = cmd;
  add_bench_options(*cmd, options->bench);
  cmd->get_option("file")->required(false)->description(
      "Character to bench (default: the baseline's scene file); not with --result");
  cmd->add_option("--baseline", options->baseline, "Baseline result (bench --json or check --update-baseline)")
      ->required();
  cmd->add_option("--result", options->result, "Compare this result of bench --json instead of running a bench");
  cmd->add_option("--metric", options->metrics,
                  "Timed metrics that must not regress: frame, or categories such as Animations, Rasterizer")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--tolerance", options->tolerance,
                  "Slowdown of the median allowed before a significant shift fails: 10% or 0.1")
      ->capture_default_str();
  cmd->add_option("--alpha", options->alpha, "Significance level of the Mann-Whitney U test")->capture_default_str();
  cmd->add_flag("--update-baseline", options->update, "Write the result as the new baseline instead of comparing");
  cmd->add_option("--csv", options->bench.csv, "Write the run's frames to this CSV file");
  cmd->add_option("--json", options->bench.json, "Write the run's result (as bench --json) to this file");
  cmd->add_option("--svg", options->svg, "Write a chart of the metric per frame, baseline against current");
  cmd->callback([&run, options] { run = [options] { return check(*options); }; });
}

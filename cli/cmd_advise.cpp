// `crowdprof advise`: how to fit this crowd in a frame budget on the CPU. The
// search is lib/advise's; here the hooks it measures through (compare's
// interleaved benches, capacity's search) and the outputs.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <memory>
#include <thread>

#include "advise/advise.h"
#include "base/errors.h"
#include "base/output_file.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "cli/compare_modes.h"
#include "frame/copy_store.h"
#include "frame/interrupt.h"
#include "frame/run_bench.h"
#include "reports/advise_report.h"
#include "reports/html_report.h"
#include "result/result_codec.h"
#include "result/result_document.h"

using namespace crowdprof;

namespace {

struct AdviseCliOptions {
  BenchCliOptions bench;
  double budget = 0;
  std::string metric = "frame";
  double max_error = 1.0;
  double time_limit = 180;
  std::string levers;  // comma-separated
  long long block = 10;
  std::string scene_out;
};

RunSpec spec_of(const RunSpec& shared, const AdviseConfig& config) {
  RunSpec spec = shared;
  spec.mode = config.preset;
  spec.switches = config.switches;
  spec.threads = config.threads;
  return spec;
}

// The settings' names in the record's texts as the options users type.
void spell_options(AdviceRecord& record) {
  record.ran_out = as_options(SettingText(record.ran_out));
  for (AdviceStep& step : record.steps)
    for (AdviceCandidate& c : step.candidates) c.verdict = as_options(SettingText(c.verdict));
}

// How many benches of the start's crowd fit in memory at once (2 at least:
// the base and one lever; check_fits_in_memory says when not even those do).
size_t benches_in_memory(const BenchScene& scene, const BenchConfig& start) {
  const uint64_t available = available_memory_bytes();
  const uint64_t one = std::max<uint64_t>(estimate_bench_bytes(scene.characters, start.crowd, start.mode), 1);
  if (available == 0) return 8;
  return std::clamp<size_t>(static_cast<size_t>(available * 9 / 10 / one), 2, 8);
}

// The largest crowd the capacities are searched up to: 64 times the crowd
// (1,000 at least, and no more than capacity's default cap, 100,000), so that
// a cheap final configuration does not search far past what was asked.
size_t capacity_cap(size_t characters) {
  return std::min<size_t>(std::max<size_t>(characters * 64, 1000), 100'000);
}

int advise(AdviseCliOptions& o) {
  check_block(o.block);
  AdviseRule rule;
  rule.budget_ms = o.budget;
  rule.max_error_px = o.max_error;
  rule.time_limit_s = o.time_limit;
  rule.levers = split_commas(o.levers);
  std::optional<CapacityMetric> metric = parse_capacity_metric(o.metric);
  if (!metric) throw UsageError("--metric '" + o.metric + "': expected frame or Animations");
  rule.metric = *metric;
  if (SettingText why = rule.Validate(); !why.empty()) throw SettingsUsageError(why);
  resolve_bench_spec(o.bench);
  // A saving is told from noise by its interval over the frames: one or two
  // frames give none.
  if (o.bench.spec.frames < 5)
    throw UsageError("--frames " + std::to_string(o.bench.spec.frames) +
                     ": advise needs at least 5 frames a configuration to tell a saving from noise");
  validate_run_spec(o.bench.spec);
  require_writable_outputs(o.bench);
  const RunSpec& spec = o.bench.spec;
  BenchScene scene = load_bench_scene(spec);
  const AdviseConfig start{spec.mode, spec.switches, spec.threads};
  BenchConfig start_config = make_bench_config(spec, scene);
  BenchRendering rendering = open_bench_rendering(o.bench, scene, start_config);
  rule.cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  rule.characters = spec.characters;
  rule.side_by_side = benches_in_memory(scene, start_config);

  auto bench_config = [&](const AdviseConfig& config) {
    BenchConfig bench = make_bench_config(spec_of(spec, config), scene);
    bench.renderer = rendering.renderer.get();
    return bench;
  };
  const auto began = std::chrono::steady_clock::now();
  auto elapsed_s = [began] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count(); };
  // The runs stop between blocks on ^C or once the time limit has passed.
  std::atomic<bool> stop{false};
  std::jthread watch([&](std::stop_token done) {
    while (!done.stop_requested() && !stop.load()) {
      if (interrupt_requested().load() || elapsed_s() >= rule.time_limit_s) stop = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  AdviseHooks hooks;
  hooks.measure = [&](std::span<const AdviseConfig> configs) {
    if (stop.load()) {
      // Stopped already: no benches built for nothing (a crowd takes seconds to make).
      std::vector<Result> cut(configs.size());
      for (Result& run : cut) run.partial = true;
      return cut;
    }
    std::vector<BenchConfig> benches;
    for (const AdviseConfig& config : configs) benches.push_back(bench_config(config));
    ModeRun run = make_benches(scene, benches, spec.characters, true, false);
    return run_modes(run, o.bench, static_cast<size_t>(o.block), rendering,
                     "advise, " + std::to_string(configs.size()) + " configurations,", &stop);
  };
  size_t rounds = 0;
  std::vector<BenchConfig> ends;
  hooks.capacity = [&](std::span<const AdviseConfig> configs) {
    ends.clear();
    std::vector<ModeCapacity> modes;
    for (const AdviseConfig& config : configs) {
      ends.push_back(bench_config(config));
      ModeCapacity mode;
      mode.mode = ends.back().mode_name;
      mode.rule.budget_ms = rule.budget_ms;
      mode.rule.cap =
          largest_crowd_in_memory(scene.characters, ends.back(), capacity_cap(spec.characters), configs.size());
      mode.rule.start = std::clamp<size_t>(spec.characters, 1, std::max<size_t>(mode.rule.cap, 1));
      modes.push_back(mode);
    }
    return run_capacity(std::move(modes), rule.metric,
                        capacity_measure(scene, ends, o.bench, static_cast<size_t>(o.block), rendering, rounds, &stop));
  };
  hooks.stop_reason = [] { return std::string(interrupt_requested().load() ? "interrupted" : "time limit"); };
  hooks.elapsed_s = elapsed_s;
  hooks.progress = [&](const std::string& line) {
    if (!o.bench.quiet) std::cerr << "crowdprof: advise: " << line << "\n";
  };
  install_interrupt_handlers();
  AdviseRun result = run_advise(rule, start, hooks);
  watch.request_stop();
  AdviceRecord& record = result.record;
  spell_options(record);
  record.frames_per_configuration = spec.frames;
  record.warmup = spec.warmup;
  record.block_frames = static_cast<size_t>(o.block);

  if (!result.start_run) {
    std::cerr << "crowdprof: " << (result.partial ? "interrupted" : "the time limit passed")
              << " before a frame of the start was measured: nothing printed or written\n";
    return result.partial ? kExitInterrupted : kExitRegression;
  }
  if (o.bench.outputs.files().prints_on_stdout(o.bench.quiet)) std::cout << format_advice(record, &*result.start_run);
  ResultDocument document;
  document.kind = "advise";
  document.partial = result.partial;
  document.advice = record;
  if (result.start_run) document.runs.push_back(*result.start_run);
  if (result.final_run) document.runs.push_back(*result.final_run);
  for (Result& run : document.runs) {
    run.run.backend = rendering.backend_name();
    run.run.renderer = rendering.renderer_name();
  }
  if (!o.bench.csv.empty()) write_text(o.bench.csv, "CSV", [&](std::ostream& out) { write_advice_csv(record, out); });
  if (!o.bench.json.empty())
    write_text(o.bench.json, "JSON", [&](std::ostream& out) {
      out << with_paths_relative_to(result_document_to_json(document), o.bench.json).dump(2) << "\n";
    });
  if (!o.bench.html.empty()) {
    HtmlReportInput input;
    add_document(input, document, "this advice");
    write_html_report(o.bench.html, std::move(input));
  }
  if (!o.scene_out.empty()) {
    write_scene_out(o.scene_out, spec_of(spec, result.final), scene, bench_config(result.final));
  }
  if (result.partial) {
    std::cerr << "crowdprof: interrupted: the plan holds the " << record.steps.size() << " whole step"
              << (record.steps.size() == 1 ? "" : "s") << " before it"
              << (o.bench.json.empty() && o.bench.csv.empty() && o.bench.html.empty() && o.scene_out.empty()
                      ? ""
                      : ", written as a partial plan")
              << "\n";
    return kExitInterrupted;
  }
  return record.met ? kExitOk : kExitRegression;
}

}  // namespace

void add_advise_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<AdviseCliOptions>();
  options->bench.defaults.values["frames"] = "40";
  options->bench.defaults.values["warmup"] = "5";
  auto* cmd = app.add_subcommand(
      "advise",
      "Find which CPU levers fit this crowd in a frame budget: a greedy search that measures each lever beside the "
      "configuration of the moment and takes the one that saves most milliseconds per pixel of drawn error (one "
      "that meets the budget alone first, with the least error; then one that adds none); exits 0 when the budget "
      "is met, 1 when not");
  cmd->footer(
      "Examples:\n  crowdprof advise scenes/thesis.json -n 2000 --budget 16.7 --scene-out fitted.json\n"
      "GPU levers (hwskin, buffer, instanced, compute, baked) are not tried: timed on a software GL they would give "
      "wrong advice.");
  add_bench_options(*cmd, options->bench);
  cmd->add_option("--budget", options->budget, "The budget in ms, e.g. 16.7 (60 fps)")->required()->type_name("MS");
  cmd->add_option("--metric", options->metric, "What must fit the budget: frame or Animations (their medians)")
      ->type_name("frame|Animations")
      ->capture_default_str();
  cmd->add_option("--max-error", options->max_error,
                  "The largest drawn error in pixels a lever may bring the crowd to (at the scene's camera and "
                  "resolution)")
      ->type_name("PX")
      ->capture_default_str();
  cmd->add_option("--time-limit", options->time_limit,
                  "Seconds the search may take: at the limit the step or capacity search running is cut and left out, "
                  "and the plan is what the whole steps found")
      ->type_name("SECONDS")
      ->capture_default_str();
  cmd->add_option("--levers", options->levers,
                  "The lever families to try (default: all of " + lever_family_names() + ")")
      ->type_name("A,B,...");
  cmd->add_option("--block", options->block, "Frames of one configuration before the next runs")->capture_default_str();
  options->bench.outputs.declare(*cmd, OutputOption::Csv, options->bench.csv,
                                 "Write one row per configuration measured, step by step");
  options->bench.outputs.declare(*cmd, OutputOption::Json, options->bench.json,
                                 "Write the plan, with the start's and the final configuration's runs");
  options->bench.outputs.declare(*cmd, OutputOption::Html, options->bench.html,
                                 "Write an HTML report: the plan first, then cost against drawn error with the path "
                                 "taken, then the start's and the final configuration's runs");
  options->bench.outputs.declare(*cmd, OutputOption::SceneOut, options->scene_out,
                                 "Write the final configuration as a scene file that bench runs as is");
  group_outputs(*cmd);
  group_options(*cmd, "Search", {"--budget", "--metric", "--max-error", "--time-limit", "--levers", "--block"});
  cmd->callback([&run, options] { run = [options] { return advise(*options); }; });
}

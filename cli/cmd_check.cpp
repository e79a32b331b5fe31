// `crowdprof check`: runs a bench (or reads a result of bench --json) and
// compares it with a baseline: exit 1 when a metric regressed beyond the
// tolerance and significantly, or when the work done (counters, digest)
// changed; exit 0 with a one-line summary otherwise. The logic is in
// lib/gate/regression.h.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "base/output_file.h"
#include "cli/bench_options.h"
#include "cli/check_against.h"
#include "cli/child_run.h"
#include "cli/spawn.h"
#include "cli/commands.h"
#include "cli/html_output.h"
#include "cli/output.h"
#include "frame/interrupt.h"
#include "frame/run_bench.h"
#include "base/switch_table.h"
#include "gate/check_plan.h"
#include "measuring/instruction_counter.h"
#include "result/pooled_runs.h"
#include "gate/regression.h"
#include "result/result_codec.h"
#include "result/run_match.h"
#include "reports/report_charts.h"
#include "base/number_text.h"
#include "reports/svg_chart.h"
#include "reports/verdict_report.h"

namespace {

using namespace crowdprof;
using nlohmann::json;

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
  bool calibrate = false;  // time the calibration probe after each frame (set by check())
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
  std::string junit, markdown;
  CLI::App* command = nullptr;  // to tell options given from defaults
  bool action_from_baseline = false;
  bool file_from_baseline = false;  // the scene file is the one the baseline recorded
};

bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  return !a.empty() && (a == b || std::filesystem::equivalent(a, b, error));
}

// Re-running a baseline: its recorded run is a layer between the scene file
// and the command line (frame/run_spec.h), so options left out take the
// baseline's values and options given override them. A value no run could
// have recorded is the baseline's fault, not the command line's: InputError.
void resolve_with_baseline(CheckCliOptions& o, const Result& baseline) {
  SpecLayer command_line = command_line_layer(o.bench);
  SpecLayer recorded = recorded_layer(baseline, o.baseline, recorded_scene_file(baseline, o.baseline));
  o.file_from_baseline = !command_line.has("file");
  o.action_from_baseline = recorded.has("action") && !command_line.has("action") && !command_line.has("actions");
  std::vector<SpecLayer> layers;
  try {
    layers = run_layers(command_line, &recorded, &o.bench.defaults);
  } catch (const InputError& e) {
    if (!o.file_from_baseline) throw;
    throw InputError(o.baseline, std::string("its scene file: ") + e.what() +
                                     " (the path the baseline recorded, resolved from the baseline's folder)");
  }
  o.bench.spec = resolve_run_spec(layers);
  validate_run_spec(o.bench.spec);
}

// The baseline named an action this character does not have: the baseline
// is of another character, which is a bad baseline rather than a bad option.
void require_recorded_action(const CheckCliOptions& o, const Character& character) {
  if (!o.action_from_baseline) return;
  std::string names;
  for (const Action& action : character.actions) {
    if (action.name == o.bench.spec.action) return;
    names += (names.empty() ? "" : ", ") + action.name;
  }
  throw InputError(o.baseline, "the baseline is of another run: its action '" + o.bench.spec.action +
                                   "' is not one of " + o.bench.spec.file + "'s (" + names + ")");
}

Result run_bench_report(CheckCliOptions& o, const std::string& progress_label) {
  BenchScene scene;
  try {
    scene = load_bench_scene(o.bench.spec);
  } catch (const InputError& e) {
    if (!o.file_from_baseline) throw;
    throw InputError(o.baseline, std::string("its scene file: ") + e.what() +
                                     " (the path the baseline recorded, resolved from the baseline's folder)");
  }
  require_recorded_action(o, scene.first());
  BenchConfig config = make_bench_config(o.bench.spec, scene);
  check_fits_in_memory(scene.characters, config);
  BenchRendering rendering = open_bench_rendering(o.bench, scene, config);
  CrowdBench bench(scene.characters, config);
  RunOptions run;
  run.frames = o.bench.spec.frames;
  run.warmup = o.bench.spec.warmup;
  run.progress = terminal_progress(o.bench.quiet, progress_label + ", mode " + config.mode_name + ",");
  install_interrupt_handlers();
  run.stop = &interrupt_requested();
  run.calibrate = o.calibrate;
  Result report = run_bench(bench, o.bench.spec.file, run);
  report.run.backend = rendering.backend_name();
  report.run.renderer = rendering.renderer_name();
  return report;
}

void write_svg(const std::string& path, const Result& baseline, const Result& current, const std::string& metric) {
  std::string shown = metric == "frame_ms" ? "frame" : metric == "cpu_ms" ? "CPU" : metric;
  const bool ratio = metric == "calibrated";  // each frame over its probe: no unit
  LineChart chart{"check: " + shown + (ratio ? " frame" : " time") + " per frame, baseline and current: " +
                      scene_caption(current),
                  "frame (0 = the first measured, after " + std::to_string(current.run.warmup) + " warm-up)",
                  ratio ? "frame over the calibration probe" : "time (ms)", {}, false};
  ModeColours colours;  // baseline and current as the HTML report colours them
  for (const auto& [name, result] : {std::pair<const char*, const Result*>{"baseline", &baseline}, {"current", &current}}) {
    LineSeries series{name, {}, result_samples(*result, metric), colours.colour(name)};
    for (size_t i = 0; i < series.y.size(); ++i) series.x.push_back(static_cast<double>(i));
    chart.series.push_back(std::move(series));
  }
  SvgDocument svg;
  svg.add(chart);
  write_text(path, "SVG", [&](std::ostream& out) { out << svg.str(); });
}

// Step 1: what to compare and how often (gate/check_plan.h).
CheckPlan plan_of(const CheckCliOptions& o) {
  CheckRequest request;
  request.metrics = o.metrics;
  request.tolerance = o.tolerance;
  request.tolerance_given = o.command->count("--tolerance") > 0;
  request.floor = o.floor;
  request.alpha = o.alpha;
  if (o.command->count("--runs") > 0) request.runs = o.runs;
  if (o.command->count("--spread") > 0) request.spread_s = o.spread;
  request.update_baseline = o.update;
  request.timings_only = o.timings_only;
  request.has_result = !o.result.empty();
  return plan_check(request);
}

// Step 2: outputs are checked before a run that would be lost, and a
// comparison never overwrites what it compares against.
void require_safe_outputs(const CheckCliOptions& o) {
  if (!o.update && same_file(o.bench.json, o.baseline))
    throw UsageError("--json " + o.bench.json + " is the baseline; to replace it, use --update-baseline");
  std::vector<NamedPath> inputs = {{"--result file", o.result}};
  if (!o.update) inputs.push_back({"baseline", o.baseline});
  std::vector<NamedPath> outputs = {{"--svg", o.svg}, {"--junit", o.junit}, {"--markdown", o.markdown}};  // --html is among the bench options
  if (o.update) outputs.push_back({"--baseline", o.baseline});
  require_writable_outputs(o.bench, inputs, outputs);
  if (!o.svg.empty()) require_writable(o.svg, "SVG");
  if (!o.junit.empty()) require_writable(o.junit, "JUnit XML");
  if (!o.markdown.empty()) require_writable(o.markdown, "Markdown");
  if (o.update) require_writable(o.baseline, "baseline");
}

// Step 3: a bad baseline is found before a long run, not after it. One being
// replaced only lends its options, if it can.
std::optional<Result> read_baseline(const CheckCliOptions& o) {
  if (!o.update) {
    std::error_code error;
    if (!std::filesystem::exists(o.baseline, error))
      throw InputError(o.baseline, "no such file (record a baseline first with --update-baseline)");
    return read_result(o.baseline);
  }
  std::error_code error;
  if (o.result.empty() && std::filesystem::exists(o.baseline, error)) {
    try {
      return read_result(o.baseline);
    } catch (const InputError& e) {
      std::cerr << "crowdprof: note: replacing a baseline that cannot be read (" << e.what() << ")\n";
    }
  }
  return std::nullopt;
}

// crowdprof's own line among a run's stderr (valgrind's banner comes first).
std::string crowdprof_line(const std::string& text) {
  size_t at = text.rfind("crowdprof: ");
  if (at != std::string::npos && (at == 0 || text[at - 1] == '\n')) return first_line(text.substr(at));
  return first_line(text);
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (size_t start = 0; start <= dirs.size();) {
    size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    std::string candidate = dirs.substr(start, end - start) + "/" + program;
    if (end > start && ::access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

// Step 4, --metric instructions: each run is this binary's bench in a process
// of its own, on one thread (waiting is never counted), counted by the CPU's
// hardware counter where the host exposes one, else under callgrind (which
// must start the process, so never a fork). A run's count is the
// instructions of its measured frames over their number.
std::optional<Result> measure_instructions(CheckCliOptions& o, const CheckPlan& plan) {
  std::string perf_problem = perf_event_problem();
  const bool callgrind = !perf_problem.empty();
  if (callgrind && !on_path("valgrind"))
    throw std::runtime_error("--metric instructions: nothing counts instructions here: no hardware counter (" +
                             perf_problem + ") and no valgrind (apt-get install valgrind)");
  RunSpec spec = o.bench.spec;
  spec.threads = 1;
  ScratchFolder scratch;
  const std::string result_path = scratch.file("run.json"), callgrind_path = scratch.file("callgrind.out");
  std::vector<std::string> bench_args = {"bench"};
  for (std::string& arg : run_spec_arguments(spec)) bench_args.push_back(std::move(arg));
  bench_args.insert(bench_args.end(), {"--count-instructions", "-q", "--json", result_path});
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  std::string program = self;
  std::vector<std::string> args = bench_args;
  if (callgrind) {
    program = "valgrind";
    args = {"--tool=callgrind", "--collect-atstart=no", "--callgrind-out-file=" + callgrind_path, self};
    args.insert(args.end(), bench_args.begin(), bench_args.end());
  }
  install_interrupt_handlers();
  std::vector<Result> runs;
  std::vector<double> counts;
  for (size_t i = 1; i <= plan.runs; ++i) {
    if (!o.bench.quiet && ::isatty(STDERR_FILENO))
      std::cerr << "\rcrowdprof: check: counting instructions" << (callgrind ? " under callgrind" : "") << ", run "
                << i << " of " << plan.runs << std::flush;
    Finished finished = run_program(program, args, scratch.file("run.err"));
    if (interrupt_requested().load()) {
      std::cerr << "\ncrowdprof: interrupted: instructions are not compared from a cut run\n";
      return std::nullopt;
    }
    if (finished.status != 0)
      throw std::runtime_error("--metric instructions: the counted run failed (exit " +
                               std::to_string(finished.status) + "): " + crowdprof_line(finished.error_text));
    Result run = read_result(result_path);
    // The run wrote its scene file relative to the scratch folder; as an
    // in-process run records it, it is the spec's (relative to here).
    run.run.file = spec.file;
    run.file_from_result = false;
    InstructionRecord& instructions = run.instructions ? *run.instructions : run.instructions.emplace();
    if (callgrind) {
      std::string problem;
      uint64_t total = callgrind_totals(callgrind_path, problem);
      if (!problem.empty()) throw std::runtime_error("--metric instructions: " + problem);
      // The frames toggle collection through valgrind's header, found at build time.
      if (total == 0)
        throw std::runtime_error("--metric instructions: callgrind counted nothing: this crowdprof was built without "
                                 "valgrind's callgrind.h (apt-get install valgrind, then build again)");
      instructions.source = "callgrind";
      instructions.per_frame = static_cast<double>(total) / static_cast<double>(std::max<size_t>(1, spec.frames));
    } else if (!instructions.per_frame) {
      throw std::runtime_error("--metric instructions: the run counted none (" +
                               (instructions.problem.empty() ? std::string("no count") : instructions.problem) + ")");
    }
    counts.push_back(*instructions.per_frame);
    runs.push_back(std::move(run));
  }
  if (!o.bench.quiet && ::isatty(STDERR_FILENO)) std::cerr << "\n";
  // The run whose count is the median, with every run's count beside it.
  std::vector<size_t> order(runs.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return counts[a] < counts[b]; });
  Result median = runs[order[(order.size() - 1) / 2]];
  median.instructions->runs = counts;
  return median;
}

// Step 4: the runs. The spec resolves as defaults, scene file, baseline,
// command line; then plan.runs runs, each a process of its own (child_run.h):
// the CPU time of one unchanged scene moves about three times more between
// processes than within one, so a baseline and a check each sample several
// processes, and the gate compares their medians. The CSV is of the last run.
// A ^C writes the frames measured so far as a partial result (--json) and
// returns nullopt.
std::optional<Result> measure(CheckCliOptions& o, const CheckPlan& plan, const std::optional<Result>& baseline) {
  if (baseline) resolve_with_baseline(o, *baseline);
  else resolve_bench_spec(o.bench);
  if (o.bench.spec.file.empty()) throw UsageError("check needs a scene FILE to run, or --result FILE");
  require_safe_outputs(o);  // the scene file may have come from the baseline
  if (plan.gate.metrics.front() == kInstructionsMetric) return measure_instructions(o, plan);
  std::vector<Result> runs;
  json partial;  // a cut run's document: written as it is, never read back
  install_interrupt_handlers();  // here, to forward a ^C to the run in progress
  auto start = std::chrono::steady_clock::now();
  for (size_t i = 1; i <= plan.runs && partial.is_null(); ++i) {
    // Run i starts (i - 1) / (runs - 1) of the way through the spread.
    if (i > 1 && plan.spread_s > 0) {
      auto due = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(
                             plan.spread_s * static_cast<double>(i - 1) / static_cast<double>(plan.runs - 1)));
      while (std::chrono::steady_clock::now() < due && !interrupt_requested().load())
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (interrupt_requested().load()) break;
    std::string label =
        plan.runs > 1 ? "check, run " + std::to_string(i) + " of " + std::to_string(plan.runs) : "check";
    auto run_started = i == 1 ? start : std::chrono::steady_clock::now();
    json doc = run_in_child_process([&] {
      Result report = run_bench_report(o, label);
      if (!o.bench.csv.empty()) write_text(o.bench.csv, "CSV", [&](std::ostream& out) { write_csv(report, out); });
      Result result = report;
      result.pid = static_cast<int64_t>(::getpid());
      return result_to_json(result);
    });
    if (is_partial_result(doc)) {
      partial = std::move(doc);
    } else {
      Result run = result_from_json(doc, "the run");
      run.started_s = std::chrono::duration<double>(run_started - start).count();
      // Another run than the baseline's is found after one run, not after all.
      if (runs.empty() && baseline && !o.update && !o.timings_only) require_same_run(*baseline, run, o.baseline);
      runs.push_back(std::move(run));
    }
  }
  if (partial.is_null() && !interrupt_requested().load()) {
    // The median run by the gate's first metric; by CPU time (else the frame)
    // when the runs were not calibrated, as the gate then falls back to it.
    std::string key = plan.gate.metrics.front();
    if (!metric_samples(runs.front(), key)) key = metric_samples(runs.front(), "cpu_ms") ? "cpu_ms" : "frame_ms";
    return pooled_runs(std::move(runs), key);
  }
  // The frames measured so far: the cut run's, or the last whole one's.
  if (partial.is_null() && !runs.empty()) {
    Result last = std::move(runs.back());
    last.pid.reset();
    last.partial = true;
    last.frames_planned = last.frames();
    partial = result_to_json(last);
  }
  if (partial.is_object()) {
    partial = as_partial_result(std::move(partial));
    if (!o.bench.json.empty())
      write_text(o.bench.json, "JSON", [&](std::ostream& out) { out << partial.dump(2) << "\n"; });
  }
  std::cerr << "crowdprof: interrupted: "
            << (o.update ? "the baseline is not updated from a partial run" : "a partial run is not compared") << "\n";
  return std::nullopt;
}

// Step 5a, --update-baseline: the result becomes the baseline.
int write_baseline(const CheckCliOptions& o, const CheckPlan& plan, const Result& current) {
  if (!o.bench.json.empty()) write_result_file(o.bench.json, "JSON", current);
  write_result_file(o.baseline, "baseline", current);
  if (!o.bench.html.empty()) {
    HtmlReportInput input;
    add_result(input, current, o.baseline);
    write_html_report(o.bench.html, std::move(input));
  }
  if (prints_on_stdout(o.bench.quiet, {o.bench.csv, o.bench.json, o.svg, o.bench.html}))
    std::cout << "baseline written: " << o.baseline << " (" << current.run.mode << ", " << current.run.characters
              << " characters, frame median " << summarize(current.samples.frame_ms).median << " ms"
              << (o.result.empty() && plan.runs > 1
                      ? ", the median of " + std::to_string(plan.runs) + " runs by " +
                            metric_display_name(plan.gate.metrics.front())
                      : "")
              << ", digest " << current.digest << ")\n";
  return kExitOk;
}

// What an instruction count was made with: counts compare only within one.
std::string instruction_origin(const InstructionRecord& i) {
  auto known = [](const std::string& text) { return text.empty() ? std::string("?") : text; };
  return known(i.source) + " (SIMD " + known(i.simd) + ", " + known(i.compiler) + ", " + std::to_string(i.threads) +
         " thread)";
}

// Step 5b for --metric instructions: the counts against the tolerance (no test
// of significance: the count does not vary with the machine), then the work.
int gate_instructions(const CheckCliOptions& o, CheckPlan plan, const Result& baseline, const Result& current) {
  if (!baseline.instructions || !baseline.instructions->per_frame)
    throw InputError(o.baseline, "has no instruction count: record one with --metric instructions --update-baseline");
  if (!current.instructions || !current.instructions->per_frame)
    throw InputError(o.result.empty() ? std::string("the run") : o.result,
                     "has no instruction count (a result of check --metric instructions, or bench --count-instructions "
                     "where hardware counters exist)");
  const std::string base_origin = instruction_origin(*baseline.instructions);
  const std::string origin = instruction_origin(*current.instructions);
  if (base_origin != origin)
    throw InputError(o.baseline, "its instructions were counted by " + base_origin + ", this run's by " + origin +
                                     ": counts compare only from the same source, SIMD target and compiler (record "
                                     "the baseline again here)");
  if (!o.timings_only) require_same_run(baseline, current, o.baseline);
  CheckOptions work = plan.gate;
  work.metrics = {"frame_ms"};  // for the counters and the digest; the frame itself is not judged
  CheckResult result = check_results(baseline, current, work);
  const double base = *baseline.instructions->per_frame;
  const double now = *current.instructions->per_frame;
  const double change = base > 0 ? now / base - 1 : 0;
  const bool slower = change > plan.gate.tolerance;
  GateTable table = check_verdict_table(result, work);
  GateRow row;
  row.metric = "instructions";
  row.unit = "instructions";
  row.base_ms = base;
  row.current_ms = now;
  row.change = change;
  row.has_p = false;
  row.verdict = slower ? "slower" : change < -plan.gate.tolerance ? "faster" : "no change";
  row.failed = slower;
  if (slower) row.why = "more instructions per frame than the " + percent(plan.gate.tolerance).substr(1) + " tolerance";
  table.metrics = {row};
  table.title = "instructions per measured frame, " + origin + ": stored baseline " + o.baseline;
  if (!o.bench.json.empty()) write_result_file(o.bench.json, "JSON", current);
  if (!o.junit.empty())
    write_text(o.junit, "JUnit XML", [&](std::ostream& out) { out << verdict_junit(table, "crowdprof check"); });
  if (!o.markdown.empty()) write_text(o.markdown, "Markdown", [&](std::ostream& out) { out << verdict_markdown(table); });
  if (prints_on_stdout(o.bench.quiet, {o.bench.json, o.junit, o.markdown})) {
    std::cout << "instructions per frame: " << fixed(base, 0) << " -> " << fixed(now, 0) << " (" << percent(change)
              << "; tolerance " << percent(plan.gate.tolerance).substr(1) << "), "
              << (slower ? "SLOWER" : row.verdict) << "; counted by " << origin << "\n";
    std::cout << "work: " << (table.work_compared ? (table.work_equal ? "the same" : "CHANGED") : "not compared")
              << " (" << table.work_detail << ")\n";
  }
  return table.failed() ? kExitRegression : kExitOk;
}

// Step 5b: the gate, then its outputs.
// Slower beyond the gate, but the same work: what a confirmation may clear.
bool only_timings_regressed(const CheckResult& result) {
  return result.regressed() && result.counters.empty() && result.counters_missing.empty() && !result.digest_differs();
}

std::string slower_metrics(const CheckResult& result) {
  std::string names;
  for (const MetricCheck& m : result.metrics)
    if (m.regressed) names += (names.empty() ? "" : ", ") + m.metric + " " + percent(m.change);
  return names;
}

// `remeasure` runs the check's runs again (empty when the result was read from
// a file): a timed failure with the work unchanged must repeat o.confirm times.
int gate(const CheckCliOptions& o, CheckPlan plan, const Result& baseline, Result current,
         const std::function<std::optional<Result>()>& remeasure) {
  if (plan.gate.metrics.front() == kInstructionsMetric) return gate_instructions(o, plan, baseline, current);
  CheckOptions& options = plan.gate;
  std::string current_name = o.result.empty() ? std::string("the run") : o.result;
  GateMetrics chosen =
      gate_metrics(baseline, current, options.metrics, o.command->count("--metric") > 0, o.baseline, current_name);
  options.metrics = std::move(chosen.metrics);
  for (const std::string& note : chosen.notes) std::cerr << "crowdprof: note: " << note << "\n";
  if (!o.timings_only) require_same_run(baseline, current, o.baseline);
  for (const std::string& note : comparison_notes(baseline, current))
    std::cerr << "crowdprof: " << (note.rfind("warning: ", 0) == 0 ? "" : "note: ") << note << "\n";
  for (const std::string& key : options.metrics)
    for (const auto& [result, path] : {std::pair{&baseline, o.baseline}, {&current, current_name}})
      if (!metric_samples(*result, key))
        throw InputError(path, "has no \"samples." + key + "\" (recorded by an older crowdprof): record it again, or "
                               "check another --metric");
  CheckResult result = check_results(baseline, current, options);
  for (long long round = 1; remeasure && round <= o.confirm && only_timings_regressed(result); ++round) {
    std::cerr << "crowdprof: note: slower than the baseline (" << slower_metrics(result)
              << ") with the same work: measuring again to confirm (" << round << " of " << o.confirm << ", --confirm)\n";
    std::optional<Result> again = remeasure();
    if (!again) return kExitInterrupted;
    current = std::move(*again);
    result = check_results(baseline, current, options);
    if (!result.regressed())
      std::cerr << "crowdprof: note: not confirmed: measured again, it is within the gate (a slow moment of the "
                   "machine, not of the build)\n";
    else if (round == o.confirm)
      std::cerr << "crowdprof: note: confirmed: slower again (" << slower_metrics(result) << ")\n";
  }
  if (!o.bench.json.empty()) write_result_file(o.bench.json, "JSON", current);
  if (!o.svg.empty()) write_svg(o.svg, baseline, current, options.metrics.front());
  if (!o.bench.html.empty()) {
    // Both runs side by side under the verdict.
    HtmlReportInput input;
    add_result(input, baseline, o.baseline);
    add_result(input, current, o.result.empty() ? "this run" : o.result);
    input.runs[0].label = "baseline";
    input.runs[1].label = "current";
    input.check = CheckSection{result, options, o.baseline};
    write_html_report(o.bench.html, std::move(input));
  }
  if (!o.junit.empty() || !o.markdown.empty()) {
    GateTable table = check_verdict_table(result, options);
    table.title = "stored baseline " + o.baseline + " against " + current_name;
    if (!o.junit.empty())
      write_text(o.junit, "JUnit XML", [&](std::ostream& out) { out << verdict_junit(table, "crowdprof check"); });
    if (!o.markdown.empty())
      write_text(o.markdown, "Markdown", [&](std::ostream& out) { out << verdict_markdown(table); });
  }
  if (prints_on_stdout(o.bench.quiet, {o.bench.csv, o.bench.json, o.svg, o.bench.html, o.junit, o.markdown}))
    std::cout << format_check(result, options);
  return result.regressed() ? kExitRegression : kExitOk;
}

// check --against BASE: the A/B of two builds (cli/check_against.h). Its
// defaults differ from a stored baseline's: the frame, and a 5% tolerance.
int check_ab(CheckCliOptions& o, CheckPlan plan) {
  for (const char* option : {"--baseline", "--result", "--update-baseline", "--runs", "--spread", "--confirm",
                             "--confirm-spread", "--svg", "--csv", "--trace", "--screenshot"})
    if (const CLI::Option* given = o.command->get_option_no_throw(option); given && given->count() > 0)
      throw UsageError(std::string(option) + " is not for an A/B: --against runs both builds and compares them");
  if (plan.gate.metrics.front() == kInstructionsMetric)
    throw UsageError("--metric instructions is for a stored baseline: an A/B times both builds side by side");
  if (o.command->count("--metric") > 0 &&
      std::find(plan.gate.metrics.begin(), plan.gate.metrics.end(), "calibrated") != plan.gate.metrics.end())
    throw UsageError("--metric calibrated is for a stored baseline: an A/B pairs both builds in time, which is what "
                     "the calibration probe does for a baseline; check frame (the default) or cpu");
  SpecLayer command_line = command_line_layer(o.bench);
  if (!command_line.has("file")) throw UsageError("check --against needs a scene FILE to run on both builds");
  resolve_bench_spec(o.bench);
  validate_run_spec(o.bench.spec);
  // Under 6 groups no paired test reaches p < 0.05 (the smallest two-sided p is 2/2^groups).
  if (o.groups < 6 || o.groups > 100)
    throw SettingError("groups", std::to_string(o.groups), "expected 6 to 100 (fewer can never be significant)");
  require_writable_outputs(o.bench, {{"--against binary", o.against}},  // --json and --html among them
                           {{"--junit", o.junit}, {"--markdown", o.markdown}});
  if (!o.junit.empty()) require_writable(o.junit, "JUnit XML");
  if (!o.markdown.empty()) require_writable(o.markdown, "Markdown");
  AgainstRequest request;
  request.base_binary = o.against;
  request.bench = &o.bench;
  request.groups = static_cast<size_t>(o.groups);
  request.gate.metrics = o.command->count("--metric") > 0 ? plan.gate.metrics : std::vector<std::string>{"frame_ms"};
  request.gate.tolerance = o.command->count("--tolerance") > 0 ? plan.gate.tolerance : kAbTolerance;
  request.gate.alpha = plan.gate.alpha;
  request.gate.floor = plan.gate.floor;
  request.gate.compare_work = !o.timings_only;
  request.json = o.bench.json;
  request.junit = o.junit;
  request.markdown = o.markdown;
  request.html = o.bench.html;
  for (const char* option : {"--metric", "--tolerance", "--floor", "--alpha", "--groups"})
    if (const CLI::Option* given = o.command->get_option(option); given->count() > 0) {
      request.gate_arguments.push_back(option);
      std::string values;
      for (const std::string& value : given->results()) values += (values.empty() ? "" : ",") + value;
      request.gate_arguments.push_back(values);
    }
  if (o.timings_only) request.gate_arguments.push_back("--timings-only");
  return check_against(request);
}

// The steps in their order.
int check(CheckCliOptions& o) {
  CheckPlan plan = plan_of(o);
  // A counted run is not a timed one: no frame times worth a file.
  if (plan.gate.metrics.front() == kInstructionsMetric)
    for (const char* option : {"--csv", "--html", "--svg", "--trace", "--screenshot"})
      if (const CLI::Option* given = o.command->get_option_no_throw(option); given && given->count() > 0)
        throw UsageError(std::string(option) + " is not written by --metric instructions (its runs are counted, "
                                                "not timed); --json, --junit and --markdown are");
  if (!o.against.empty()) return check_ab(o, std::move(plan));
  if (o.baseline.empty())
    throw UsageError("check needs --baseline FILE (a stored result) or --against BINARY (an A/B of two builds)");
  SpecLayer command_line = command_line_layer(o.bench);
  if (command_line.has("file")) o.bench.spec.file = command_line.values["file"];
  if (!o.result.empty() && command_line.has("file"))
    throw UsageError("give either a scene FILE to run or --result FILE to read, not both");
  require_safe_outputs(o);
  std::optional<Result> baseline = read_baseline(o);
  // The probe's workers spin on into the next frame, where CPU time counts them:
  // runs are calibrated when a new baseline gates on the calibrated frame, or
  // when the baseline was calibrated, so that both sides' CPU time counts alike.
  const std::vector<std::string>& metrics = plan.gate.metrics;
  o.calibrate = o.update ? std::find(metrics.begin(), metrics.end(), "calibrated") != metrics.end()
                         : baseline && !baseline->samples.probe_ms.empty();
  std::optional<Result> current = o.result.empty() ? measure(o, plan, baseline) : read_result(o.result);
  if (!current) return kExitInterrupted;
  if (o.update) return write_baseline(o, plan, *current);
  std::function<std::optional<Result>()> remeasure;
  CheckPlan confirming = plan;
  confirming.spread_s = std::max(plan.spread_s, o.confirm_spread);
  if (o.result.empty()) remeasure = [&] { return measure(o, confirming, baseline); };
  return gate(o, plan, *baseline, std::move(*current), remeasure);
}

}  // namespace

void add_check_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<CheckCliOptions>();
  auto* cmd = app.add_subcommand("check", "Run a bench (or read a result) and compare it with a baseline: exit 1 "
                                          "when it got slower or its work changed (see docs/compare-and-check.md)");
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
  cmd->add_option("--groups", options->groups,
                  "With --against: ABBA groups of four processes (two of each build)")
      ->capture_default_str();
  cmd->add_option("--junit", options->junit,
                  "Write the verdict as JUnit XML: a test case per metric and one for the work, the verdict as a "
                  "failure's message");
  cmd->add_option("--markdown", options->markdown,
                  "Write the verdict as a Markdown table (a CI job summary or a pull-request comment)");
  cmd->add_option("--result", options->result, "Compare this result of bench --json instead of running a bench");
  cmd->add_option("--metric", options->metrics,
                  "Timed metrics that must not regress: calibrated (the wall-clock frame over a fixed calibration "
                  "probe timed right after it on the same threads, so a change of the machine's speed falls on both; "
                  "a baseline or --result without it is checked on cpu; not with --against), cpu (CPU time of every thread in the frame, waiting "
                  "workers' spinning included), frame (wall clock), categories such as Animations, Rasterizer, or all: the frame and every category "
                  "(Holm-corrected together); or instructions: instructions per frame on one thread (hardware "
                  "counter, else callgrind), tolerance 1%, one run")
      ->delimiter(',')
      ->allow_extra_args(false)  // one comma-separated value: a file after it stays the file
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
  cmd->add_option("--confirm", options->confirm,
                  "When a timed metric fails and the work is the same, measure again this many times and fail only if "
                  "each fails too (a machine shared with other jobs is slow for seconds at a time); 0 to 10, 0: fail at once")
      ->check(CLI::Range(0, 10).description(""))
      ->capture_default_str();
  cmd->add_option("--confirm-spread", options->confirm_spread,
                  "Seconds a confirmation spreads its runs over, so that they sample the machine before, during and "
                  "after a slow spell (at least --spread); 0 to 3600")
      ->check(CLI::Range(0.0, 3600.0).description(""))
      ->capture_default_str();
  cmd->add_flag("--timings-only", options->timings_only,
                "Compare timings alone, of runs that may differ (another crowd size): for measuring the gate itself "
                "(tests/scripts/measure_gate.sh); counters and digest are not compared");
  cmd->add_flag("--update-baseline", options->update, "Write the result as the new baseline instead of comparing");
  cmd->add_option("--csv", options->bench.csv, "Write the run's frames to this CSV file");
  cmd->add_option("--json", options->bench.json, "Write the run's result (as bench --json) to this file");
  cmd->add_option("--svg", options->svg, "Write a chart of the metric per frame, baseline against current");
  cmd->add_option("--html", options->bench.html,
                  "Write an HTML report: the verdict per metric against the tolerance, baseline and current side by side");
  group_outputs(*cmd);
  group_options(*cmd, kGateGroup,
                {"--baseline", "--against", "--groups", "--result", "--metric", "--tolerance", "--floor", "--runs",
                 "--spread", "--alpha", "--confirm", "--confirm-spread", "--timings-only",
                 "--update-baseline"});
  cmd->callback([&run, options] { run = [options] { return check(*options); }; });
}

#include "gate/check_run.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <thread>

#include "base/errors.h"
#include "base/number_text.h"
#include "base/output_file.h"
#include "base/switch_table.h"
#include "frame/interrupt.h"
#include "frame/run_bench.h"
#include "gate/ab_run.h"
#include "gate/counted_runs.h"
#include "gate/processes.h"
#include "measuring/environment.h"
#include "measuring/instruction_counter.h"
#include "measuring/other_load.h"
#include "render/bench_rendering.h"
#include "result/pooled_runs.h"
#include "result/result_codec.h"
#include "result/run_match.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// What a stored-baseline check learns as it goes: the run spec, resolved from
// the command line over the baseline's recorded run.
struct CheckState {
  const CheckRun& r;
  RunSpec spec;
  bool calibrate = false;  // time the calibration probe after each frame
  bool action_from_baseline = false;
  bool file_from_baseline = false;  // the scene file is the one the baseline recorded
  OtherLoad load;                   // what other processes took during the last timed runs
};

bool same_path(const std::string& a, const std::string& b) {
  std::error_code error;
  return !a.empty() && (a == b || std::filesystem::equivalent(a, b, error));
}

// Re-running a baseline: its recorded run is a layer between the scene file
// and the command line (frame/run_spec.h), so options left out take the
// baseline's values and options given override them. A value no run could
// have recorded is the baseline's fault, not the command line's: InputError.
void resolve_with_baseline(CheckState& s, const Result& baseline) {
  const SpecLayer& command_line = s.r.command_line;
  SpecLayer recorded = recorded_layer(baseline, s.r.baseline, recorded_scene_file(baseline, s.r.baseline));
  s.file_from_baseline = !command_line.has("file");
  s.action_from_baseline = recorded.has("action") && !command_line.has("action") && !command_line.has("actions");
  std::vector<SpecLayer> layers;
  try {
    layers = run_layers(command_line, &recorded, &s.r.defaults);
  } catch (const InputError& e) {
    if (!s.file_from_baseline) throw;
    throw InputError(s.r.baseline, std::string("its scene file: ") + e.what() +
                                       " (the path the baseline recorded, resolved from the baseline's folder)");
  }
  s.spec = resolve_run_spec(layers);
  validate_run_spec(s.spec);
}

// The baseline named an action this character does not have: the baseline
// is of another character, which is a bad baseline rather than a bad option.
void require_recorded_action(const CheckState& s, const Character& character) {
  if (!s.action_from_baseline) return;
  std::string names;
  for (const Action& action : character.actions) {
    if (action.name == s.spec.action) return;
    names += (names.empty() ? "" : ", ") + action.name;
  }
  throw InputError(s.r.baseline, "the baseline is of another run: its action '" + s.spec.action + "' is not one of " +
                                     s.spec.file + "'s (" + names + ")");
}

std::string spelled(const CheckRun& r, const SettingText& text) {
  return text.str([&](std::string_view setting) {
    return r.option_name ? r.option_name(setting) : option_spelling(std::string(setting));
  });
}

Result run_bench_report(const CheckState& s, const std::string& progress_label) {
  BenchScene scene;
  try {
    scene = load_bench_scene(s.spec);
  } catch (const InputError& e) {
    if (!s.file_from_baseline) throw;
    throw InputError(s.r.baseline, std::string("its scene file: ") + e.what() +
                                       " (the path the baseline recorded, resolved from the baseline's folder)");
  }
  require_recorded_action(s, scene.first());
  BenchConfig config = make_bench_config(s.spec, scene);
  check_fits_in_memory(scene.characters, config);
  SettingText warning;
  BenchRendering rendering = open_bench_rendering(s.spec, scene, config, &warning);
  if (!warning.empty()) std::cerr << "crowdprof: warning: " << spelled(s.r, warning) << "\n";
  CrowdBench bench(scene.characters, config);
  RunOptions run;
  run.frames = s.spec.frames;
  run.warmup = s.spec.warmup;
  run.progress = terminal_progress(s.r.quiet, progress_label + ", mode " + config.mode_name + ",");
  install_interrupt_handlers();
  run.stop = &interrupt_requested();
  run.calibrate = s.calibrate;
  Result report = run_bench(bench, s.spec.file, run);
  report.run.backend = rendering.backend_name();
  report.run.renderer = rendering.renderer_name();
  return report;
}

// Outputs are checked before a run that would be lost, and a comparison never
// overwrites what it compares against.
void require_safe_outputs(const CheckRun& r, const std::string& file) {
  const bool update = r.plan.update_baseline;
  const std::string json = r.files.path("--json");
  if (!update && same_path(json, r.baseline))
    throw UsageError("--json " + json + " is the baseline; to replace it, use --update-baseline");
  std::vector<NamedPath> inputs = bench_input_files(file);
  inputs.push_back({"--result file", r.result});
  if (!update) inputs.push_back({"baseline", r.baseline});
  OutputFiles files = r.files;
  if (update) files.add("--baseline", "baseline", r.baseline);
  files.require_usable(inputs);
}

// What --update-baseline may replace when it cannot read it as a baseline:
// not a regular file (a device, a pipe: written in place), an empty file, or
// a bench result of crowdprof's (an older format, a cut run). Anything else is
// a user's file at a mistyped path, or another command's result.
bool replaceable_baseline(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return true;
  try {
    const nlohmann::json doc = read_json_file(path);
    return doc.is_object() && doc.contains("crowdprof") && doc["crowdprof"].is_object() &&
           document_kind(doc) == "bench";
  } catch (const InputError& e) {
    return std::string(e.what()).find("empty file") != std::string::npos;
  }
}

// A bad baseline is found before a long run, not after it. One being replaced
// only lends its options (not with --result), if it can.
std::optional<Result> read_baseline(const CheckRun& r) {
  if (!r.plan.update_baseline) {
    std::error_code error;
    if (!std::filesystem::exists(r.baseline, error))
      throw InputError(r.baseline, "no such file (record a baseline first with --update-baseline)");
    return read_result(r.baseline);
  }
  std::error_code error;
  if (is_standard_output(r.baseline) || !std::filesystem::exists(r.baseline, error)) return std::nullopt;
  try {
    Result replaced = read_result(r.baseline);
    if (r.result.empty()) return replaced;
  } catch (const InputError& e) {
    if (!replaceable_baseline(r.baseline))
      throw UsageError("refusing to replace --baseline " + std::string(e.what()) +
                       ": --update-baseline replaces only a result of crowdprof bench or check (choose another "
                       "path)");
    if (std::filesystem::is_regular_file(r.baseline, error))
      std::cerr << "crowdprof: note: replacing a baseline that cannot be read (" << e.what() << ")\n";
  }
  return std::nullopt;
}

// --metric instructions: the spec's runs counted (gate/counted_runs.h).
std::optional<Result> count_instructions(CheckState& s, const CheckPlan& plan, const std::optional<Result>&) {
  try {
    std::optional<Result> counted = count_instruction_runs(s.spec, plan.runs, s.r.quiet);
    if (!counted) std::cerr << "crowdprof: interrupted: instructions are not compared from a cut run\n";
    return counted;
  } catch (const CountProblem& e) {
    throw std::runtime_error(std::string("--metric instructions: ") + e.what());
  }
}

// Timed runs: plan.runs runs, each a process of its own (gate/processes.h):
// the CPU time of one unchanged scene moves about three times more between
// processes than within one, so a baseline and a check each sample several
// processes, and the gate compares their medians. The CSV is of the last run.
// A ^C writes the frames measured so far as a partial result (--json) and
// returns nullopt.
std::optional<Result> time_runs(CheckState& s, const CheckPlan& plan, const std::optional<Result>& baseline) {
  const CheckRun& r = s.r;
  std::vector<Result> runs;
  json partial;                  // a cut run's document: written as it is, never read back
  install_interrupt_handlers();  // here, to forward a ^C to the run in progress
  OtherLoadMeter others;
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
    json doc = run_in_child_process(
        [&] {
          Result report = run_bench_report(s, label);
          if (r.each_run) r.each_run(report);
          Result result = report;
          result.pid = static_cast<int64_t>(::getpid());
          return result_to_json(result);
        },
        r.report_exception);
    if (is_partial_result(doc)) {
      partial = std::move(doc);
    } else {
      Result run = result_from_json(doc, "the run");
      run.started_s = std::chrono::duration<double>(run_started - start).count();
      // Another run than the baseline's is found after one run, not after all.
      if (runs.empty() && baseline && !r.plan.update_baseline && !r.plan.timings_only)
        require_same_run(*baseline, run, r.baseline);
      runs.push_back(std::move(run));
    }
  }
  if (partial.is_null() && !interrupt_requested().load()) {
    // The median run by the gate's first metric; by CPU time (else the frame)
    // when the runs were not calibrated, as the gate then falls back to it.
    std::string key = plan.gate.metrics.front();
    if (!metric_samples(runs.front(), key)) key = metric_samples(runs.front(), "cpu_ms") ? "cpu_ms" : "frame_ms";
    s.load = others.read();
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
    if (const std::string json = r.files.path("--json"); !json.empty())
      write_text(json, "JSON", [&](std::ostream& out) { out << partial.dump(2) << "\n"; });
  }
  std::cerr << "crowdprof: interrupted: "
            << (r.plan.update_baseline ? "the baseline is not updated from a partial run"
                                       : "a partial run is not compared")
            << "\n";
  return std::nullopt;
}

using MakeRuns = std::optional<Result> (*)(CheckState&, const CheckPlan&, const std::optional<Result>&);

// The runs: the spec resolves as defaults, scene file, baseline, command line;
// then `runs` makes them.
std::optional<Result> measure(CheckState& s, const CheckPlan& plan, const std::optional<Result>& baseline,
                              MakeRuns runs) {
  if (baseline)
    resolve_with_baseline(s, *baseline);
  else
    s.spec = resolve_run_spec(run_layers(s.r.command_line, nullptr, &s.r.defaults));
  if (s.spec.file.empty()) throw UsageError("check needs a scene FILE to run, or --result FILE");
  require_safe_outputs(s.r, s.spec.file);  // the scene file may have come from the baseline
  return runs(s, plan, baseline);
}

// What a judge may do again once the first runs are in: run them again (a
// confirmation), count this build's instructions as the baseline's work
// witness was counted, and read what other processes took during the last
// runs. Empty where the result was read from a file.
struct Remeasure {
  std::function<std::optional<Result>()> runs;
  CountWork count;
  std::function<OtherLoad()> load;
};

// The counts against the tolerance (no test of significance: the count does
// not vary with the machine), then the work.
void judge_count(const CheckRun& r, CheckOutcome& outcome, const Remeasure&) {
  const Result& baseline = *outcome.baseline;
  const Result& current = outcome.current;
  if (!baseline.instructions || !baseline.instructions->per_frame)
    throw InputError(r.baseline, "has no instruction count: record one with --metric instructions --update-baseline");
  if (baseline.instructions->frames > 0)
    throw InputError(r.baseline, "its instructions are a timed baseline's work witness, counted over " +
                                     std::to_string(baseline.instructions->frames) +
                                     " frames: record an instruction baseline with --metric instructions "
                                     "--update-baseline");
  if (!current.instructions || !current.instructions->per_frame)
    throw InputError(r.result.empty() ? std::string("the run") : r.result,
                     "has no instruction count (a result of check --metric instructions, or bench --count-instructions "
                     "where hardware counters exist)");
  const std::string base_origin = instruction_origin(*baseline.instructions);
  CountCheck& count = outcome.count;
  count.origin = instruction_origin(*current.instructions);
  if (base_origin != count.origin)
    throw InputError(r.baseline, "its instructions were counted by " + base_origin + ", this run's by " + count.origin +
                                     ": counts compare only from the same source, SIMD target and compiler (record "
                                     "the baseline again here)");
  if (!r.plan.timings_only) require_same_run(baseline, current, r.baseline);
  CheckOptions work = outcome.plan.gate;
  work.metrics = {"frame_ms"};  // for the counters and the digest; the frame itself is not judged
  outcome.result = check_results(baseline, current, work);
  count.base = *baseline.instructions->per_frame;
  count.current = *current.instructions->per_frame;
  count.change = count.base > 0 ? count.current / count.base - 1 : 0;
  count.slower = count.change > outcome.plan.gate.tolerance;
  count.faster = count.change < -outcome.plan.gate.tolerance;
  outcome.kind = CheckOutcome::Kind::Counted;
}

// Slower beyond the gate, but the same work: what a confirmation may clear.
bool only_timings_regressed(const CheckResult& result) {
  return result.regressed() && result.counters.empty() && result.counters_missing.empty() && !result.digest_differs();
}

// The median beyond the tolerance and floor but not significant (runs too
// spread to test), with the same counters and digest.
std::vector<MetricCheck*> untested_slowdowns(CheckResult& result) {
  std::vector<MetricCheck*> slower;
  if (result.regressed() || !result.counters.empty() || !result.counters_missing.empty() || result.digest_differs())
    return slower;
  for (MetricCheck& m : result.metrics)
    if (m.tested && m.beyond_tolerance && m.beyond_floor && !m.significant) slower.push_back(&m);
  return slower;
}

std::string slower_metrics(const CheckResult& result) {
  std::string names;
  for (const MetricCheck& m : result.metrics)
    if (m.regressed) names += (names.empty() ? "" : ", ") + m.metric + " " + percent(m.change);
  return names;
}

// Why the count decides as it does, for the note on stderr.
std::string witness_note(const WorkWitness& w) {
  switch (w.verdict) {
    case WorkWitness::Verdict::MoreWork:
      return "beyond the " + percent(w.tolerance).substr(1) + " tolerance, " +
             (w.runs_differ ? "the runs' own work (--timings-only)" : "the build's own slowdown") +
             ": not measured again";
    case WorkWitness::Verdict::OtherWork:
      return "other work than the baseline's, within the tolerance: the timed verdict stands";
    case WorkWitness::Verdict::MachineMoved:
    case WorkWitness::Verdict::SameMachine:
      break;
  }
  return "the same work";
}

// Only metrics timed on the CPU regressed: instructions say nothing of the GPU.
bool only_cpu_metrics_regressed(const CheckResult& result) {
  return std::all_of(result.metrics.begin(), result.metrics.end(),
                     [](const MetricCheck& m) { return !m.regressed || cpu_timed_metric(m.metric); });
}

// The timed gate. `remeasure` runs the check's runs again (empty when the
// result was read from a file): a timed failure with the work unchanged must
// repeat r.confirm times. Where the baseline holds a work witness, a timed
// failure is counted first: more instructions fail it at once, the same
// instructions on a machine seen to have changed make the confirmed slowdown
// a warning (gate/work_witness.h).
void judge_timings(const CheckRun& r, CheckOutcome& outcome, const Remeasure& remeasure) {
  const Result& baseline = *outcome.baseline;
  Result& current = outcome.current;
  CheckOptions& options = outcome.plan.gate;
  std::string current_name = r.result.empty() ? std::string("the run") : r.result;
  GateMetrics chosen = gate_metrics(baseline, current, options.metrics, r.metric_given, r.baseline, current_name);
  options.metrics = std::move(chosen.metrics);
  for (const std::string& note : chosen.notes)
    std::cerr << "crowdprof: " << (note.rfind("warning: ", 0) == 0 ? "" : "note: ") << note << "\n";
  if (!r.plan.timings_only) require_same_run(baseline, current, r.baseline);
  for (const std::string& note : comparison_notes(baseline, current))
    std::cerr << "crowdprof: " << (note.rfind("warning: ", 0) == 0 ? "" : "note: ") << note << "\n";
  for (const std::string& key : options.metrics)
    for (const auto& [result, path] : {std::pair{&baseline, r.baseline}, {&current, current_name}})
      if (!metric_samples(*result, key))
        throw InputError(path, "has no \"samples." + key +
                                   "\" (recorded by an older crowdprof): record it again, or "
                                   "check another --metric");
  CheckResult result = check_results(baseline, current, options);
  // The work witness first, where the baseline holds one (gate/work_witness.h).
  std::vector<MetricCheck*> unsure = untested_slowdowns(result);
  std::optional<WorkWitness> witness;
  if (!unsure.empty() || only_timings_regressed(result)) {
    std::string slower = slower_metrics(result);
    for (const MetricCheck* m : unsure)
      slower += (slower.empty() ? "" : ", ") + m->metric + " " + percent(m->change) + ", not significant";
    witness = witness_count(baseline, current, remeasure.count, remeasure.load, slower, options.tolerance);
    if (interrupt_requested().load()) {
      outcome.kind = CheckOutcome::Kind::Interrupted;
      return;
    }
    if (witness) {
      witness->runs_differ = r.plan.timings_only;
      std::cerr << "crowdprof: note: instructions per frame " << percent(witness->change) << ": "
                << witness_note(*witness) << "\n";
    }
  }
  const bool more_work = witness && witness->verdict == WorkWitness::Verdict::MoreWork;
  if (!unsure.empty()) {
    // A median far beyond the tolerance that the test cannot call (runs in
    // two groups, as beside a neighbour): work grown as much fails it.
    if (more_work)
      for (MetricCheck* m : unsure) m->regressed = m->work_grew = true;
    result.witness = std::move(witness);
    outcome.result = std::move(result);
    outcome.kind = CheckOutcome::Kind::Gated;
    return;
  }
  bool confirmed = false;
  for (long long round = 1; remeasure.runs && !more_work && round <= r.confirm && only_timings_regressed(result);
       ++round) {
    std::cerr << "crowdprof: note: slower than the baseline (" << slower_metrics(result)
              << ") with the same work: measuring again to confirm (" << round << " of " << r.confirm
              << ", --confirm)\n";
    std::optional<Result> again = remeasure.runs();
    if (!again) {
      outcome.kind = CheckOutcome::Kind::Interrupted;
      return;
    }
    current = std::move(*again);
    result = check_results(baseline, current, options);
    if (!result.regressed())
      std::cerr << "crowdprof: note: not confirmed: measured again, it is within the gate (a slow moment of the "
                   "machine, not of the build)\n";
    else if (round == r.confirm) {
      std::cerr << "crowdprof: note: confirmed: slower again (" << slower_metrics(result) << ")\n";
      confirmed = true;
    }
  }
  if (witness && !only_timings_regressed(result)) witness.reset();  // cleared by the confirmation
  if (witness && !more_work) {
    // Decided again on the machine of the last runs, the confirmation's.
    observe_machine(*witness, baseline, current, remeasure.load ? remeasure.load() : OtherLoad{});
    if (confirmed && witness->excuses() && only_cpu_metrics_regressed(result)) {
      std::cerr << "crowdprof: warning: slower than the baseline (" << slower_metrics(result)
                << "), confirmed, but with the same instructions per frame (" << percent(witness->change)
                << ") on a machine that was not as it was for the baseline: " << witness->machine()
                << ". Not a failure: a stored baseline cannot tell this from a slower build; time the change "
                   "against its base build with check --against BASE_BINARY\n";
      result.excuse_timings();
    }
  }
  result.witness = std::move(witness);
  outcome.result = std::move(result);
  outcome.kind = CheckOutcome::Kind::Gated;
}

// How a stored-baseline check's runs are made and judged: timed (forked,
// spread, confirmed) or counted (--metric instructions: spawned, against the
// tolerance alone). The one place the two part.
struct CheckWay {
  MakeRuns runs;
  void (*judge)(const CheckRun&, CheckOutcome&, const Remeasure&);
};

CheckWay way_of(const CheckPlan& plan) {
  if (plan.counted()) return {count_instructions, judge_count};
  return {time_runs, judge_timings};
}

CheckOutcome check_outcome(const CheckRun& r) {
  CheckRequest asked = r.plan;
  asked.ab = !r.against.empty();
  for (const char* option : {"--csv", "--html", "--svg", "--trace", "--screenshot"})
    if (r.was_given(option)) asked.timed_outputs.push_back(option);
  CheckPlan plan = plan_check(asked);
  if (!r.against.empty()) return run_ab(r, plan);
  if (r.baseline.empty())
    throw UsageError("check needs --baseline FILE (a stored result) or --against BINARY (an A/B of two builds)");
  CheckState state{r, {}};
  if (r.command_line.has("file")) state.spec.file = r.command_line.values.at("file");
  if (!r.result.empty() && r.command_line.has("file"))
    throw UsageError("give either a scene FILE to run or --result FILE to read, not both");
  require_safe_outputs(r, state.spec.file);
  CheckOutcome outcome;
  outcome.plan = plan;
  outcome.baseline = read_baseline(r);
  // The probe's workers spin on into the next frame, where CPU time counts them:
  // runs are calibrated when a new baseline gates on the calibrated frame, or
  // when the baseline was calibrated, so that both sides' CPU time counts alike.
  const std::vector<std::string>& metrics = plan.gate.metrics;
  state.calibrate = r.plan.update_baseline ? std::find(metrics.begin(), metrics.end(), "calibrated") != metrics.end()
                                           : outcome.baseline && !outcome.baseline->samples.probe_ms.empty();
  const CheckWay way = way_of(plan);
  std::optional<Result> current =
      r.result.empty() ? measure(state, plan, outcome.baseline, way.runs) : read_result(r.result);
  if (!current) return outcome;
  outcome.current = std::move(*current);
  if (r.plan.update_baseline) {
    if (!plan.counted() && r.count_work && r.result.empty()) {
      std::string problem;
      std::optional<InstructionRecord> witness =
          count_work(state.spec, std::min(state.spec.frames, kWitnessFrames),
                     std::min(state.spec.warmup, kWitnessWarmup), r.quiet, problem);
      if (interrupt_requested().load()) {
        std::cerr << "crowdprof: interrupted: the baseline is not updated\n";
        return outcome;
      }
      if (witness)
        outcome.current.instructions = std::move(*witness);
      else
        std::cerr << "crowdprof: note: the baseline holds no instruction count (" << problem
                  << "): a check that runs slower against it cannot tell a changed machine from a slower build "
                     "(--count-work off skips the count)\n";
    }
    outcome.kind = CheckOutcome::Kind::BaselineWritten;
    return outcome;
  }
  Remeasure remeasure;
  CheckPlan confirming = plan;
  confirming.spread_s = std::max(plan.spread_s, r.confirm_spread);
  if (r.result.empty()) {
    remeasure.runs = [&] { return measure(state, confirming, outcome.baseline, way.runs); };
    remeasure.count = [&](const InstructionRecord& like, std::string& problem) {
      return count_work(state.spec, like.frames, like.warmup, r.quiet, problem);
    };
    remeasure.load = [&] { return state.load; };
  }
  way.judge(r, outcome, remeasure);
  return outcome;
}

}  // namespace

CheckOutcome run_check(const CheckRun& request) {
  const auto start = std::chrono::steady_clock::now();
  CheckOutcome outcome = check_outcome(request);
  outcome.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

}  // namespace crowdprof

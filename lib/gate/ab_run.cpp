#include "gate/ab_run.h"

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
#include "gate/processes.h"
#include "measuring/environment.h"
#include "measuring/instruction_counter.h"
#include "render/bench_rendering.h"
#include "result/pooled_runs.h"
#include "result/result_codec.h"
#include "result/run_match.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// ---- check --against BASE: an A/B of two builds at the same moment
// (gate/ab_check.h). Both builds are run as processes of their own, the current
// one as well (this binary), with the same bench options, in ABBA groups; the
// verdict compares their paired ratios.

// The bench options the command line gave, as arguments both builds accept:
// only what was given, so the base build applies its own defaults to the rest
// as the current one does.
std::vector<std::string> ab_bench_arguments(const SpecLayer& command_line,
                                            const std::map<std::string, std::string>& overrides = {}) {
  SpecLayer given = command_line;
  for (const auto& [name, text] : overrides) given.values[name] = text;
  std::vector<std::string> args = {"bench", given.values.at("file")};
  for (const auto& [name, text] : given.values) {
    if (name == "file" || name == "static") continue;
    args.push_back(option_spelling(name));
    args.push_back(text);
  }
  if (given.has("static")) args.push_back("--static");
  args.push_back("-q");
  return args;
}

std::string shell_quoted(const std::string& text) {
  if (!text.empty() &&
      text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,+:%") ==
          std::string::npos)
    return text;
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct AbBuild {
  std::string label;  // "base" or "current"
  std::string binary;
  std::string version;
};

// The version line of a crowdprof binary, or InputError naming it.
std::string require_crowdprof(const std::string& binary, const ScratchFolder& scratch) {
  struct stat info {};
  if (::stat(binary.c_str(), &info) != 0)
    throw InputError(binary, "no such file (--against names the base build's crowdprof binary)");
  if (!S_ISREG(info.st_mode)) throw InputError(binary, "not a regular file (--against names a crowdprof binary)");
  if (::access(binary.c_str(), X_OK) != 0)
    throw InputError(binary, "not executable (chmod +x it, or name the built binary)");
  Finished version = run_program(binary, {"--version"}, scratch.file("version.err"), scratch.file("version.out"));
  std::ifstream in(scratch.file("version.out"));
  std::string line;
  std::getline(in, line);
  if (version.status != 0 || line.rfind("crowdprof ", 0) != 0)
    throw InputError(binary, "not crowdprof: '--version' " +
                                 (version.status != 0 ? "exited with status " + std::to_string(version.status)
                                                      : "printed '" + line.substr(0, 80) + "'"));
  return line;
}

// One process of `build`: its result, read and validated as this build reads
// results. A base whose run fails or writes what this build cannot read is
// the base's fault (InputError naming it); the current build's is a failed run.
std::optional<Result> run_ab_process(const AbBuild& build, const std::vector<std::string>& bench_args,
                                     const ScratchFolder& scratch, const std::string& name) {
  std::string result_path = scratch.file(name + ".json");
  std::vector<std::string> args = bench_args;
  args.push_back("--json");
  args.push_back(result_path);
  Finished finished = run_program(build.binary, args, scratch.file(name + ".err"));
  if (interrupt_requested().load()) return std::nullopt;
  auto fail = [&](const std::string& why) -> Result {
    if (build.label == "base") throw InputError(build.binary, "the base build " + why);
    throw std::runtime_error("this build " + why);
  };
  if (finished.status != 0)
    return fail("failed its run (exit " + std::to_string(finished.status) +
                "): " + (finished.error_text.empty() ? "no message" : first_line(finished.error_text)));
  Result result;
  try {
    result = read_result(result_path);
  } catch (const InputError& e) {
    return fail(std::string("wrote a result this build cannot read: ") + e.what());
  }
  result.wall_s = finished.wall_s;
  return result;
}

json ab_process_record(const AbBuild& build, size_t group, size_t position, const Result& result,
                       const AbProcess& process) {
  return {{"build", build.label},           {"group", group},
          {"position", position},           {"wall_s", result.wall_s.value_or(0.0)},
          {"median_ms", process.median_ms}, {"digest", process.digest}};
}

// The A/B's own refusals and defaults: its defaults differ from a stored
// baseline's (the frame, and a 5% tolerance).
AbOptions ab_gate_of(const CheckRun& r, const CheckPlan& plan) {
  for (const char* option : {"--baseline", "--result", "--update-baseline", "--runs", "--spread", "--confirm",
                             "--confirm-spread", "--svg", "--csv", "--trace", "--screenshot"})
    if (r.was_given(option))
      throw UsageError(std::string(option) + " is not for an A/B: --against runs both builds and compares them");
  if (r.metric_given &&
      std::find(plan.gate.metrics.begin(), plan.gate.metrics.end(), "calibrated") != plan.gate.metrics.end())
    throw UsageError(
        "--metric calibrated is for a stored baseline: an A/B pairs both builds in time, which is what "
        "the calibration probe does for a baseline; check frame (the default) or cpu");
  if (!r.command_line.has("file")) throw UsageError("check --against needs a scene FILE to run on both builds");
  RunSpec spec = resolve_run_spec(run_layers(r.command_line, nullptr, &r.defaults));
  validate_run_spec(spec);
  // Under 6 groups no paired test reaches p < 0.05 (the smallest two-sided p is 2/2^groups).
  if (r.groups < 6 || r.groups > 100)
    throw SettingError("groups", std::to_string(r.groups), "expected 6 to 100 (fewer can never be significant)");
  std::vector<NamedPath> inputs = bench_input_files(spec.file);
  inputs.push_back({"--against binary", r.against});
  r.files.require_usable(inputs);
  AbOptions gate;
  gate.metrics = r.metric_given ? plan.gate.metrics : std::vector<std::string>{"frame_ms"};
  gate.tolerance = r.plan.tolerance_given ? plan.gate.tolerance : kAbTolerance;
  gate.alpha = plan.gate.alpha;
  gate.floor = plan.gate.floor;
  gate.compare_work = !r.plan.timings_only;
  return gate;
}

}  // namespace

// The base binary is checked before anything runs: InputError naming it when
// it is missing, not a regular executable file, not crowdprof, or when a
// one-frame run of the same options gives no result this build reads.
CheckOutcome run_ab(const CheckRun& r, const CheckPlan& plan) {
  CheckOutcome outcome;
  outcome.plan = plan;
  AbRun& ab = outcome.ab.emplace();
  ab.gate = ab_gate_of(r, plan);
  install_interrupt_handlers();  // a ^C reaches the run in progress, then ends the A/B (exit 130)
  ScratchFolder scratch;
  auto start = std::chrono::steady_clock::now();
  // Absolute, so that a name without a slash is the file named, not one on PATH.
  const std::string base_binary = std::filesystem::absolute(r.against).string();
  AbBuild base{"base", base_binary, require_crowdprof(base_binary, scratch)};
  AbBuild current{"current", std::filesystem::read_symlink("/proc/self/exe").string(), version_line()};
  ab.bench_args = ab_bench_arguments(r.command_line);

  // Before any measured run: both builds run one frame of the same options
  // and their results must be ones this build reads, of the same run.
  std::vector<std::string> probe_args = ab_bench_arguments(r.command_line, {{"frames", "1"}, {"warmup", "0"}});
  std::optional<Result> base_probe = run_ab_process(base, probe_args, scratch, "probe-base");
  if (!base_probe) return outcome;
  std::optional<Result> current_probe = run_ab_process(current, probe_args, scratch, "probe-current");
  if (!current_probe) return outcome;
  // Runs of other settings (the base reads an option otherwise) are other
  // work: judged and reported as such, with the setting that differs.
  std::string run_difference;
  if (ab.gate.compare_work) try {
      require_same_run(*base_probe, *current_probe, base.binary);
    } catch (const InputError& e) {
      run_difference = e.what();
      size_t from = run_difference.find("another run: ");
      if (from != std::string::npos) run_difference = run_difference.substr(from + 13);
      run_difference = run_difference.substr(0, run_difference.find(" (rerun"));
    }

  for (const std::string& key : ab.gate.metrics)
    for (const Result* probe : {&*base_probe, &*current_probe})
      if (!metric_samples(*probe, key))
        throw InputError(probe == &*base_probe ? base.binary : current.binary,
                         "its results have no \"samples." + key + "\": check another --metric");

  const bool show_progress = !r.quiet && ::isatty(STDERR_FILENO);
  std::vector<AbGroup> groups;
  for (size_t g = 0; g < static_cast<size_t>(r.groups); ++g) {
    AbGroup group;
    group.base_first = g % 2 == 0;
    // ABBA, then BAAB: each build is as often first as last.
    const AbBuild* order[4] = {&base, &current, &current, &base};
    if (!group.base_first) order[0] = order[3] = &current, order[1] = order[2] = &base;
    int base_seen = 0, current_seen = 0;
    if (show_progress)
      std::cerr << "\rcrowdprof: check --against: group " << (g + 1) << " of " << r.groups << std::flush;
    for (size_t position = 0; position < 4; ++position) {
      const AbBuild& build = *order[position];
      std::optional<Result> result = run_ab_process(
          build, ab.bench_args, scratch, build.label + "-" + std::to_string(g) + "-" + std::to_string(position));
      if (!result) {
        std::cerr << "\ncrowdprof: interrupted: an A/B cut short is not judged\n";
        return outcome;
      }
      AbProcess process = ab_process(*result);
      ab.processes.push_back(ab_process_record(build, g, position, *result, process));
      if (&build == &base)
        group.base[base_seen++] = std::move(process), ab.last_base = std::move(*result);
      else
        group.current[current_seen++] = std::move(process), ab.last_current = std::move(*result);
    }
    groups.push_back(std::move(group));
  }
  if (show_progress) std::cerr << "\n";
  ab.result = judge_ab(groups, ab.gate);
  if (!run_difference.empty()) {
    ab.result.work.run_difference = run_difference;
    ab.result.work.equal = false;
  }
  ab.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ab.base_binary = base.binary;
  ab.base_version = base.version;
  ab.current_binary = current.binary;
  ab.current_version = current.version;
  std::string reproduce = "crowdprof check";
  for (size_t i = 1; i < ab.bench_args.size() - 1; ++i)
    reproduce += " " + shell_quoted(ab.bench_args[i]);  // no "bench", no -q
  for (const std::string& arg : r.gate_arguments) reproduce += " " + shell_quoted(arg);
  reproduce += " --against " + shell_quoted(base.binary);
  ab.reproduce = reproduce;
  outcome.kind = CheckOutcome::Kind::Ab;
  return outcome;
}

json AbRun::document() const {
  json metrics = json::array();
  for (const AbMetric& metric : result.metrics)
    metrics.push_back({{"metric", metric_display_name(metric.metric)},
                       {"key", metric.metric},
                       {"base_ms", metric.base_ms},
                       {"current_ms", metric.current_ms},
                       {"current_median_ms", metric.current_median_ms},
                       {"change", metric.change.median},
                       {"change_low", metric.change.low},
                       {"change_high", metric.change.high},
                       {"confidence", gate.confidence},
                       {"ratios", metric.ratios},
                       {"p", metric.test.p},
                       {"p_adjusted", metric.p_adjusted},
                       {"exact_p", metric.test.exact},
                       {"floor_ms", metric.floor_ms},
                       {"verdict", metric.regressed  ? "slower"
                                   : metric.improved ? "faster"
                                                     : "no change"}});
  json counters = json::array();
  for (const CounterDifference& c : result.work.counters)
    counters.push_back({{"name", c.name}, {"base", c.baseline}, {"current", c.current}});
  return {
      {"crowdprof", {{"version", last_current.environment.version}, {"format", kResultFormat}, {"kind", "ab_check"}}},
      {"builds",
       {{"base", {{"binary", base_binary}, {"version", base_version}, {"environment", environment_to_json(last_base)}}},
        {"current",
         {{"binary", current_binary},
          {"version", current_version},
          {"environment", environment_to_json(last_current)}}}}},
      {"bench_arguments", bench_args},
      {"tolerance", gate.tolerance},
      {"alpha", gate.alpha},
      {"metrics", metrics},
      {"work",
       {{"compared", result.work.compared},
        {"equal", result.work.equal},
        {"base_digest", result.work.base_digest},
        {"current_digest", result.work.current_digest},
        {"counters_differing", counters}}},
      {"processes", processes},
      {"wall_s", wall_s},
      {"regressed", result.regressed()}};
}

}  // namespace crowdprof

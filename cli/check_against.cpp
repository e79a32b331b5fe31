#include "cli/check_against.h"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "base/errors.h"
#include "cli/html_output.h"
#include "cli/spawn.h"
#include "cli/output.h"
#include "frame/interrupt.h"
#include "base/switch_table.h"
#include "base/output_file.h"
#include "measuring/environment.h"
#include "gate/regression.h"
#include "result/result_codec.h"
#include "result/run_match.h"
#include "reports/verdict_report.h"

namespace check_against_impl {

using namespace crowdprof;
using nlohmann::json;
namespace fs = std::filesystem;

// The bench options the command line gave, as arguments both builds accept:
// only what was given, so the base build applies its own defaults to the rest
// as the current one does.
std::vector<std::string> bench_arguments(const BenchCliOptions& bench,
                                         const std::map<std::string, std::string>& overrides = {}) {
  SpecLayer given = command_line_layer(bench);
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
  if (!text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,+:%") ==
                           std::string::npos)
    return text;
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct Build {
  std::string label;  // "base" or "current"
  std::string binary;
  std::string version;
};

// The version line of a crowdprof binary, or InputError naming it.
std::string require_crowdprof(const std::string& binary, const ScratchFolder& scratch) {
  struct stat info {};
  if (::stat(binary.c_str(), &info) != 0) throw InputError(binary, "no such file (--against names the base build's crowdprof binary)");
  if (!S_ISREG(info.st_mode)) throw InputError(binary, "not a regular file (--against names a crowdprof binary)");
  if (::access(binary.c_str(), X_OK) != 0) throw InputError(binary, "not executable (chmod +x it, or name the built binary)");
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
std::optional<Result> run_once(const Build& build, const std::vector<std::string>& bench_args,
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
    return fail("failed its run (exit " + std::to_string(finished.status) + "): " +
                (finished.error_text.empty() ? "no message" : first_line(finished.error_text)));
  Result result;
  try {
    result = read_result(result_path);
  } catch (const InputError& e) {
    return fail(std::string("wrote a result this build cannot read: ") + e.what());
  }
  result.wall_s = finished.wall_s;
  return result;
}

json process_record(const Build& build, size_t group, size_t position, const Result& result, const AbProcess& process) {
  return {{"build", build.label},         {"group", group},
          {"position", position},         {"wall_s", result.wall_s.value_or(0.0)},
          {"median_ms", process.median_ms}, {"digest", process.digest}};
}

json ab_document(const AbResult& result, const AbOptions& options, const Build& base, const Build& current,
                 const std::vector<std::string>& bench_args, const json& processes, double wall_s,
                 const Result& base_result, const Result& current_result) {
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
                       {"confidence", options.confidence},
                       {"ratios", metric.ratios},
                       {"p", metric.test.p},
                       {"p_adjusted", metric.p_adjusted},
                       {"exact_p", metric.test.exact},
                       {"floor_ms", metric.floor_ms},
                       {"verdict", metric.regressed ? "slower" : metric.improved ? "faster" : "no change"}});
  json counters = json::array();
  for (const CounterDifference& c : result.work.counters)
    counters.push_back({{"name", c.name}, {"base", c.baseline}, {"current", c.current}});
  return {{"crowdprof", {{"version", current_result.environment.version}, {"format", kResultFormat},
                         {"kind", "ab_check"}}},
          {"builds",
           {{"base", {{"binary", base.binary}, {"version", base.version}, {"environment", environment_to_json(base_result)}}},
            {"current",
             {{"binary", current.binary}, {"version", current.version}, {"environment", environment_to_json(current_result)}}}}},
          {"bench_arguments", bench_args},
          {"tolerance", options.tolerance},
          {"alpha", options.alpha},
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

}  // namespace check_against_impl

int check_against(const AgainstRequest& request) {
  using namespace check_against_impl;
  install_interrupt_handlers();  // a ^C reaches the run in progress, then ends the A/B (exit 130)
  ScratchFolder scratch;
  auto start = std::chrono::steady_clock::now();
  // Absolute, so that a name without a slash is the file named, not one on PATH.
  const std::string base_binary = fs::absolute(request.base_binary).string();
  Build base{"base", base_binary, require_crowdprof(base_binary, scratch)};
  Build current{"current", fs::read_symlink("/proc/self/exe").string(), version_line()};
  std::vector<std::string> bench_args = bench_arguments(*request.bench);

  // Before any measured run: both builds run one frame of the same options
  // and their results must be ones this build reads, of the same run.
  std::vector<std::string> probe_args = bench_arguments(*request.bench, {{"frames", "1"}, {"warmup", "0"}});
  std::optional<Result> base_probe = run_once(base, probe_args, scratch, "probe-base");
  if (!base_probe) return kExitInterrupted;
  std::optional<Result> current_probe = run_once(current, probe_args, scratch, "probe-current");
  if (!current_probe) return kExitInterrupted;
  // Runs of other settings (the base reads an option otherwise) are other
  // work: judged and reported as such, with the setting that differs.
  std::string run_difference;
  if (request.gate.compare_work) try {
      require_same_run(*base_probe, *current_probe, base.binary);
    } catch (const InputError& e) {
      run_difference = e.what();
      size_t from = run_difference.find("another run: ");
      if (from != std::string::npos) run_difference = run_difference.substr(from + 13);
      run_difference = run_difference.substr(0, run_difference.find(" (rerun"));
    }

  AbOptions gate = request.gate;
  for (const std::string& key : gate.metrics)
    for (const Result* probe : {&*base_probe, &*current_probe})
      if (!metric_samples(*probe, key))
        throw InputError(probe == &*base_probe ? base.binary : current.binary,
                         "its results have no \"samples." + key + "\": check another --metric");

  const bool show_progress = !request.bench->quiet && ::isatty(STDERR_FILENO);
  std::vector<AbGroup> groups;
  json processes = json::array();
  Result last_base, last_current;
  for (size_t g = 0; g < request.groups; ++g) {
    AbGroup group;
    group.base_first = g % 2 == 0;
    // ABBA, then BAAB: each build is as often first as last.
    const Build* order[4] = {&base, &current, &current, &base};
    if (!group.base_first) order[0] = order[3] = &current, order[1] = order[2] = &base;
    int base_seen = 0, current_seen = 0;
    if (show_progress)
      std::cerr << "\rcrowdprof: check --against: group " << (g + 1) << " of " << request.groups << std::flush;
    for (size_t position = 0; position < 4; ++position) {
      const Build& build = *order[position];
      std::optional<Result> result =
          run_once(build, bench_args, scratch, build.label + "-" + std::to_string(g) + "-" + std::to_string(position));
      if (!result) {
        std::cerr << "\ncrowdprof: interrupted: an A/B cut short is not judged\n";
        return kExitInterrupted;
      }
      AbProcess process = ab_process(*result);
      processes.push_back(process_record(build, g, position, *result, process));
      if (&build == &base) group.base[base_seen++] = std::move(process), last_base = std::move(*result);
      else group.current[current_seen++] = std::move(process), last_current = std::move(*result);
    }
    groups.push_back(std::move(group));
  }
  if (show_progress) std::cerr << "\n";
  AbResult result = judge_ab(groups, gate);
  if (!run_difference.empty()) {
    result.work.run_difference = run_difference;
    result.work.equal = false;
  }
  double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  GateTable table = ab_verdict_table(result, gate);
  std::ostringstream title;
  title << "A/B: " << request.groups << " groups (ABBA/BAAB), " << 4 * request.groups << " processes, "
        << std::fixed << std::setprecision(1) << wall_s << " s\n  base:    " << base.version << "\n  current: " << current.version;
  table.title = title.str();
  std::string reproduce = "crowdprof check";
  for (size_t i = 1; i < bench_args.size() - 1; ++i) reproduce += " " + shell_quoted(bench_args[i]);  // no "bench", no -q
  for (const std::string& arg : request.gate_arguments) reproduce += " " + shell_quoted(arg);
  reproduce += " --against " + shell_quoted(base.binary);
  table.reproduce = reproduce;

  if (!request.json.empty()) {
    json document = ab_document(result, gate, base, current, bench_args, processes, wall_s, last_base, last_current);
    write_text(request.json, "JSON", [&](std::ostream& out) { out << document.dump(2) << "\n"; });
  }
  if (!request.junit.empty())
    write_text(request.junit, "JUnit XML", [&](std::ostream& out) { out << verdict_junit(table, "crowdprof check --against"); });
  if (!request.markdown.empty())
    write_text(request.markdown, "Markdown", [&](std::ostream& out) { out << verdict_markdown(table); });
  if (!request.html.empty()) {
    HtmlReportInput input;
    add_result(input, last_base, base.binary);
    add_result(input, last_current, current.binary);
    input.runs[0].label = "base";
    input.runs[1].label = "current";
    write_html_report(request.html, std::move(input));
  }
  if (prints_on_stdout(request.bench->quiet, {request.json, request.junit, request.markdown, request.html}))
    std::cout << verdict_text(table);
  return result.regressed() ? kExitRegression : kExitOk;
}

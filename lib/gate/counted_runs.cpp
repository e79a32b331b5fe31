#include "gate/counted_runs.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "base/errors.h"
#include "frame/interrupt.h"
#include "gate/processes.h"
#include "measuring/instruction_counter.h"
#include "result/result_codec.h"

namespace crowdprof {

namespace {

// crowdprof's own line among a run's stderr (valgrind's banner comes first).
std::string crowdprof_line(const std::string& text) {
  size_t at = text.rfind("crowdprof: ");
  if (at != std::string::npos && (at == 0 || text[at - 1] == '\n')) return first_line(text.substr(at));
  return first_line(text);
}

}  // namespace

std::optional<Result> count_instruction_runs(const RunSpec& run_spec, size_t count, bool quiet) {
  std::string perf_problem = perf_event_problem();
  const bool callgrind = !perf_problem.empty();
  if (callgrind && !on_path("valgrind"))
    throw CountProblem("nothing counts instructions here: no hardware counter (" + perf_problem +
                       ") and no valgrind (apt-get install valgrind)");
  if (callgrind && sanitizer_build())
    throw CountProblem("valgrind cannot run a sanitizer build, and no hardware counter opens here (" + perf_problem +
                       ")");
  RunSpec spec = run_spec;
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
  for (size_t i = 1; i <= count; ++i) {
    if (!quiet && ::isatty(STDERR_FILENO))
      std::cerr << "\rcrowdprof: check: counting instructions" << (callgrind ? " under callgrind" : "") << ", run " << i
                << " of " << count << std::flush;
    Finished finished = run_program(program, args, scratch.file("run.err"));
    if (interrupt_requested().load()) {
      if (!quiet && ::isatty(STDERR_FILENO)) std::cerr << "\n";
      return std::nullopt;
    }
    if (finished.status != 0)
      throw CountProblem("the counted run failed (exit " + std::to_string(finished.status) +
                         "): " + crowdprof_line(finished.error_text));
    Result run = read_result(result_path);
    // The run wrote its scene file relative to the scratch folder; as an
    // in-process run records it, it is the spec's (relative to here).
    run.run.file = spec.file;
    run.file_from_result = false;
    InstructionRecord& instructions = run.instructions ? *run.instructions : run.instructions.emplace();
    if (callgrind) {
      std::string problem;
      uint64_t total = callgrind_totals(callgrind_path, problem);
      if (!problem.empty()) throw CountProblem(problem);
      // The frames toggle collection through valgrind's header, found at build time.
      if (total == 0)
        throw CountProblem(
            "callgrind counted nothing: this crowdprof was built without "
            "valgrind's callgrind.h (apt-get install valgrind, then build again)");
      instructions.source = "callgrind";
      instructions.per_frame = static_cast<double>(total) / static_cast<double>(std::max<size_t>(1, spec.frames));
    } else if (!instructions.per_frame) {
      throw CountProblem("the run counted none (" +
                         (instructions.problem.empty() ? std::string("no count") : instructions.problem) + ")");
    }
    counts.push_back(*instructions.per_frame);
    runs.push_back(std::move(run));
  }
  if (!quiet && ::isatty(STDERR_FILENO)) std::cerr << "\n";
  // The run whose count is the median, with every run's count beside it.
  std::vector<size_t> order(runs.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return counts[a] < counts[b]; });
  Result median = runs[order[(order.size() - 1) / 2]];
  median.instructions->runs = counts;
  return median;
}

std::optional<InstructionRecord> count_work(const RunSpec& run_spec, size_t frames, size_t warmup, bool quiet,
                                            std::string& problem) {
  RunSpec spec = run_spec;
  spec.frames = frames;
  spec.warmup = warmup;
  try {
    std::optional<Result> run = count_instruction_runs(spec, 1, quiet);
    if (!run || !run->instructions || !run->instructions->per_frame) {
      problem = "the count was interrupted";
      return std::nullopt;
    }
    InstructionRecord record = *run->instructions;
    record.frames = frames;
    record.warmup = warmup;
    record.runs.clear();
    return record;
  } catch (const CountProblem& e) {
    problem = e.what();
    return std::nullopt;
  }
}

}  // namespace crowdprof

// Instructions counted rather than time measured: this binary's bench in a
// process of its own, on one thread (waiting is never counted), counted by the
// CPU's hardware counter where the host exposes one, else under callgrind
// (which must start the process, so never a fork). For check --metric
// instructions, and for a timed baseline's work witness (gate/work_witness.h).
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

#include "frame/run_spec.h"
#include "result/result.h"

namespace crowdprof {

// Why nothing was counted: no counter here, or a counted run that failed (its
// own line). Callers say what the count was for.
struct CountProblem : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `count` counted runs of `spec` (its threads set to 1); each run's count is
// the instructions of its measured frames over their number. The run whose
// count is the median, every run's count in its instructions.runs; nullopt
// after a ^C (the caller says so). CountProblem where nothing counts or a run failed.
std::optional<Result> count_instruction_runs(const RunSpec& spec, size_t count, bool quiet);

// One count of `frames` frames after `warmup` of `spec`, as a work witness
// records it (its frames and warmup set). Nullopt, with `problem` set, where
// nothing counts here, the counted run failed or was cut.
std::optional<InstructionRecord> count_work(const RunSpec& spec, size_t frames, size_t warmup, bool quiet,
                                            std::string& problem);

}  // namespace crowdprof

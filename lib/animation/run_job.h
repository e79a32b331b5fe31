// Jobs have ozz-animation's shape: a plain struct of inputs and outputs with
// Validate() and Run(), and Run() returns false, writing nothing, when the
// inputs break the job's contract. Inside crowdprof the caller builds those
// inputs, so a false is a bug, not bad input: run_job stops the run with a
// runtime error (exit 4) instead of going on with stale output.
#pragma once

#include <stdexcept>
#include <string>

namespace crowdprof {

template <typename Job>
void run_job(const Job& job, const char* name) {
  if (!job.Run()) [[unlikely]]
    throw std::logic_error(std::string(name) + " rejected its inputs (a bug in crowdprof; please report it)");
}

}  // namespace crowdprof

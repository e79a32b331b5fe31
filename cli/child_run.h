// Measured runs in processes of their own. The CPU time of one unchanged scene
// moves about three times more between processes than within one (where the
// kernel puts a process's buffers and threads stays with it for its life), so
// a gate that compares one process against another must sample processes, not
// only frames (docs/compare-and-check.md has the measurement).
#pragma once

#include <functional>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace crowdprof {

// A child process printed its own error line and exited with `status`: the
// parent exits with the same status and prints nothing more.
struct ChildFailed : std::runtime_error {
  explicit ChildFailed(int exit_status)
      : std::runtime_error("a measured run failed with exit status " + std::to_string(exit_status)),
        status(exit_status) {}
  int status;
};

// Runs `work` in a fork of this process and returns the JSON it returned. The
// child has its own process group, so the terminal's ^C reaches this process
// only, which forwards SIGINT and SIGTERM to the child (frame/interrupt.h): the
// first signal lets the child end its frame and return a partial result, a
// second ends both. The child dies with this process. An exception in the
// child is reported there on stderr (report_current_exception) and becomes
// ChildFailed here; a child killed by a signal is a std::runtime_error.
// Call only while this process has one thread: a fork copies only the thread
// that calls it, and a thread pool started before would hang in the child.
nlohmann::json run_in_child_process(const std::function<nlohmann::json()>& work);

// Prints one line on stderr for the exception being handled ("crowdprof: ...")
// and returns its exit status (base/errors.h: 2 usage, 3 bad input, 4 failed
// run). Call only inside a catch block.
int report_current_exception();

// The command being run ("bench"), so that a bad option value is reported as
// "bench: --fps 'x': ... (see crowdprof bench --help)".
void set_current_command(const std::string& command);

}  // namespace crowdprof

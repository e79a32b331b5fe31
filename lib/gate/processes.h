// Runs in processes of their own: forks of this one for measured runs, and
// programs started anew where a fork will not do: another build (check
// --against), or this binary under valgrind (check --metric instructions).
// The CPU time of one unchanged scene moves about three times more between
// processes than within one (where the kernel puts a process's buffers and
// threads stays with it for its life), so a gate that compares one process
// against another must sample processes, not only frames
// (docs/compare-and-check.md has the measurement).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace crowdprof {

// A temporary folder, removed with everything in it when it goes.
class ScratchFolder {
 public:
  ScratchFolder();
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  std::string file(const std::string& name) const;

 private:
  std::string path_;
};

struct Finished {
  int status = 0;          // the exit status, or 128 + the signal; 127 when it could not start
  std::string error_text;  // what it wrote on stderr
  double wall_s = 0;
};

// Runs `program` (a path, or a name looked up on PATH) with `args`, stdin from
// /dev/null, stdout to `stdout_path`, stderr to `stderr_path` (read back), not
// through a shell. A ^C reaches it and this process waits for it to end.
Finished run_program(const std::string& program, const std::vector<std::string>& args, const std::string& stderr_path,
                     const std::string& stdout_path = "/dev/null");

// The first line of a program's message.
std::string first_line(const std::string& text);

// Whether `program` is an executable file in a folder of PATH.
bool on_path(const std::string& program);

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
// child is reported there by `report_exception` (called in a catch block; it
// prints the error and returns the exit status) and becomes ChildFailed here;
// a child killed by a signal is a std::runtime_error.
// Call only while this process has one thread: a fork copies only the thread
// that calls it, and a thread pool started before would hang in the child.
nlohmann::json run_in_child_process(const std::function<nlohmann::json()>& work,
                                    const std::function<int()>& report_exception);

}  // namespace crowdprof

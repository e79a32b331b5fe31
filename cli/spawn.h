// Programs run as processes of their own, for the runs that must not be forks
// of this one: another build (check --against), or this binary under valgrind
// (check --metric instructions).
#pragma once

#include <string>
#include <vector>

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

#include "cli/spawn.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "frame/interrupt.h"

extern char** environ;

namespace fs = std::filesystem;

ScratchFolder::ScratchFolder() {
  std::string pattern = (fs::temp_directory_path() / "crowdprof-runs-XXXXXX").string();
  if (!::mkdtemp(pattern.data()))
    throw std::runtime_error("cannot make a temporary folder in " + fs::temp_directory_path().string() + ": " +
                             std::strerror(errno));
  path_ = pattern;
}

ScratchFolder::~ScratchFolder() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

std::string ScratchFolder::file(const std::string& name) const { return (fs::path(path_) / name).string(); }

Finished run_program(const std::string& program, const std::vector<std::string>& args, const std::string& stderr_path,
                     const std::string& stdout_path) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  int spawned = posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  Finished finished;
  if (spawned != 0) {
    finished.status = 127;
    finished.error_text = std::string("cannot run it: ") + std::strerror(spawned);
    return finished;
  }
  forward_interrupts_to(pid);
  int status = 0;
  pid_t waited = 0;
  while ((waited = ::waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
  }
  forward_interrupts_to(0);
  if (waited < 0) {
    finished.status = 127;
    finished.error_text = std::string("cannot wait for it: ") + std::strerror(errno);
    return finished;
  }
  finished.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  finished.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::ifstream in(stderr_path);
  std::stringstream text;
  text << in.rdbuf();
  finished.error_text = text.str();
  while (!finished.error_text.empty() && finished.error_text.back() == '\n') finished.error_text.pop_back();
  return finished;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

#include "gate/processes.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "base/errors.h"
#include "frame/interrupt.h"

extern char** environ;

namespace fs = std::filesystem;

namespace crowdprof {

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

std::string ScratchFolder::file(const std::string& name) const {
  return (fs::path(path_) / name).string();
}

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

std::string first_line(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (size_t start = 0; start <= dirs.size();) {
    size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    std::string candidate = dirs.substr(start, end - start) + "/" + program;
    if (end > start && ::access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

namespace {

[[noreturn]] void forked_child_main(const std::function<nlohmann::json()>& work,
                                    const std::function<int()>& report_exception, int out) {
  int status = kExitOk;
  try {
    std::string text = work().dump();
    for (size_t done = 0; done < text.size();) {
      ssize_t n = ::write(out, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw std::runtime_error(std::string("cannot hand a run's result over: ") + std::strerror(errno));
      done += static_cast<size_t>(n);
    }
  } catch (...) {
    status = report_exception();
  }
  std::cout.flush();
  std::fflush(nullptr);
  // _exit: no destructors or atexit handlers of the parent's state run twice.
  ::_exit(status);
}

std::string read_child_output(int in) {
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    ssize_t n = ::read(in, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(std::string("cannot read a run's result: ") + std::strerror(errno));
    if (n == 0) return text;
    text.append(buffer, static_cast<size_t>(n));
  }
}

}  // namespace

nlohmann::json run_in_child_process(const std::function<nlohmann::json()>& work,
                                    const std::function<int()>& report_exception) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot start a measured run: pipe: ") + std::strerror(errno));
  std::cout.flush();
  std::fflush(nullptr);  // what is buffered would be written twice, once by each process
  pid_t parent = ::getpid();
  pid_t child = ::fork();
  if (child < 0) {
    int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("cannot start a measured run: fork: ") + std::strerror(error));
  }
  if (child == 0) {
    ::close(fds[0]);
    ::setpgid(0, 0);                     // ^C from the terminal goes to the parent, which forwards it once
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the parent
    if (::getppid() != parent) ::_exit(kExitRuntime);
    forked_child_main(work, report_exception, fds[1]);
  }
  ::close(fds[1]);
  forward_interrupts_to(child);
  // A signal taken between the fork and the line above was not forwarded.
  if (interrupt_requested().load()) ::kill(child, SIGINT);
  std::string text;
  try {
    text = read_child_output(fds[0]);
  } catch (...) {
    ::kill(child, SIGKILL);
    forward_interrupts_to(0);
    ::close(fds[0]);
    ::waitpid(child, nullptr, 0);
    throw;
  }
  ::close(fds[0]);
  int raw = 0;
  while (::waitpid(child, &raw, 0) < 0 && errno == EINTR) {
  }
  forward_interrupts_to(0);
  if (WIFSIGNALED(raw))
    throw std::runtime_error(std::string("a measured run was ended by signal ") + std::to_string(WTERMSIG(raw)) + " (" +
                             strsignal(WTERMSIG(raw)) + ")");
  if (WEXITSTATUS(raw) != kExitOk) throw ChildFailed(WEXITSTATUS(raw));
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    throw std::runtime_error("a measured run handed over a result that is not JSON (" + std::to_string(text.size()) +
                             " bytes)");
  }
}

}  // namespace crowdprof

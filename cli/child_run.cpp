#include "cli/child_run.h"

#include "cli/bench_options.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>
#include <string>

#include "base/errors.h"
#include "frame/interrupt.h"

namespace crowdprof {

namespace {
std::string current_command;
}  // namespace

void set_current_command(const std::string& command) { current_command = command; }

namespace {
// An error's text with the settings it names spelled as the options the user typed.
std::string as_typed(const std::exception& e) {
  if (const auto* names = dynamic_cast<const NamesSettings*>(&e))
    return names->spelled([](std::string_view setting) { return option_name(std::string(setting)); });
  return e.what();
}
}  // namespace

int report_current_exception() {
  try {
    throw;
  } catch (const ChildFailed& e) {
    return e.status;  // the child said why
  } catch (const InputError& e) {
    std::cerr << "crowdprof: " << as_typed(e) << "\n";
    return kExitBadInput;
  } catch (const SettingError& e) {
    // lib/ names the setting; the user typed its option.
    std::cerr << "crowdprof: " << (current_command.empty() ? "" : current_command + ": ") << option_name(e.name)
              << " '" << e.value << "': " << e.why
              << (current_command.empty() ? "" : " (see crowdprof " + current_command + " --help)") << "\n";
    return kExitUsage;
  } catch (const UsageError& e) {
    std::cerr << "crowdprof: " << as_typed(e) << "\n";
    return kExitUsage;
  } catch (const std::bad_alloc&) {
    std::cerr << "crowdprof: out of memory\n";
    return kExitRuntime;
  } catch (const std::exception& e) {
    std::cerr << "crowdprof: " << as_typed(e) << "\n";
    return kExitRuntime;
  }
}

namespace {

[[noreturn]] void child_main(const std::function<nlohmann::json()>& work, int out) {
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
    status = report_current_exception();
  }
  std::cout.flush();
  std::fflush(nullptr);
  // _exit: no destructors or atexit handlers of the parent's state run twice.
  ::_exit(status);
}

std::string read_all(int in) {
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

nlohmann::json run_in_child_process(const std::function<nlohmann::json()>& work) {
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
    ::setpgid(0, 0);                      // ^C from the terminal goes to the parent, which forwards it once
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the parent
    if (::getppid() != parent) ::_exit(kExitRuntime);
    child_main(work, fds[1]);
  }
  ::close(fds[1]);
  forward_interrupts_to(child);
  // A signal taken between the fork and the line above was not forwarded.
  if (interrupt_requested().load()) ::kill(child, SIGINT);
  std::string text;
  try {
    text = read_all(fds[0]);
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
    throw std::runtime_error(std::string("a measured run was ended by signal ") + std::to_string(WTERMSIG(raw)) +
                             " (" + strsignal(WTERMSIG(raw)) + ")");
  if (WEXITSTATUS(raw) != kExitOk) throw ChildFailed(WEXITSTATUS(raw));
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    throw std::runtime_error("a measured run handed over a result that is not JSON (" + std::to_string(text.size()) +
                             " bytes)");
  }
}

}  // namespace crowdprof

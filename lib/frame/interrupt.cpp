#include "frame/interrupt.h"

#include <signal.h>
#include <sys/types.h>

namespace {

std::atomic<bool> requested{false};
std::atomic<pid_t> forward_to{0};
static_assert(std::atomic<pid_t>::is_always_lock_free, "read in a signal handler");

extern "C" void on_interrupt(int signal_number) {
  if (pid_t child = forward_to.load(); child > 0) ::kill(child, signal_number);
  if (!requested.exchange(true)) return;
  // The second signal: the default action (end the process) at once.
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

const std::atomic<bool>& interrupt_requested() {
  return requested;
}

void forward_interrupts_to(int pid) {
  forward_to.store(static_cast<pid_t>(pid));
}

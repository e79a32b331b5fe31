#include "frame/interrupt.h"

#include <signal.h>

namespace {

std::atomic<bool> requested{false};

extern "C" void on_interrupt(int signal_number) {
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

const std::atomic<bool>& interrupt_requested() { return requested; }

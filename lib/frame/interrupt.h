// ^C during a run (bench, compare, check): the first SIGINT or SIGTERM asks the run to stop after the
// frame in progress (the frames measured so far are reported and written, and
// the command exits 130); a second one ends the process at once, as if no
// handler were installed.
#pragma once

#include <atomic>

// Installs the handlers; safe to call more than once.
void install_interrupt_handlers();

// Set by the first signal; the frame loops read it between frames.
const std::atomic<bool>& interrupt_requested();

// While `pid` is not 0, every SIGINT or SIGTERM this process takes is also sent
// to process `pid` (a run measured in a child process of its own, which the
// terminal's ^C does not reach): the first asks it to stop after its frame, a
// second ends both at once. 0 stops forwarding.
void forward_interrupts_to(int pid);

// The exit status after an interrupt: 128 + SIGINT, as shells report ^C.
inline constexpr int kExitInterrupted = 130;

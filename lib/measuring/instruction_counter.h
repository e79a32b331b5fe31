// Instructions of the measured frames: a count of the work that does not move
// with the machine's speed or load, for a stored baseline that a shared
// machine cannot make drift (check --metric instructions). Counted on the
// frame's own thread only, so waiting is never counted: a run that counts
// instructions runs on one thread (--threads 1).
//   perf_event: the CPU's retired-instruction counter (perf_event_open), read
//     before and after each frame, where the host exposes hardware counters;
//   callgrind: under valgrind --tool=callgrind --collect-atstart=no, the frame
//     toggles collection on and off (client requests), and whoever ran
//     valgrind reads the total from callgrind's output (callgrind_totals).
#pragma once

#include <cstdint>
#include <string>

namespace crowdprof {

// What bench --count-instructions does, as its --help says it.
inline constexpr const char* kCountInstructionsHelp =
    "Count each measured frame's instructions on one thread: perf_event's hardware counter, or "
    "callgrind's under valgrind --tool=callgrind --collect-atstart=no (check --metric instructions runs "
    "that); recorded in --json as \"instructions\"";

enum class InstructionSource { None, PerfEvent, Callgrind };

// "perf_event", "callgrind", "none".
const char* instruction_source_name(InstructionSource source);

class InstructionCounter {
 public:
  InstructionCounter() = default;  // counts nothing
  InstructionCounter(const InstructionCounter&) = delete;
  InstructionCounter& operator=(const InstructionCounter&) = delete;
  InstructionCounter(InstructionCounter&& other) noexcept;
  InstructionCounter& operator=(InstructionCounter&& other) noexcept;
  ~InstructionCounter();

  // Callgrind when the process runs under it, else the hardware counter of
  // the calling thread, else none (why_none() says why).
  static InstructionCounter open();

  InstructionSource source() const { return source_; }
  const std::string& why_none() const { return why_none_; }

  void begin_frame();
  // The frame's instructions with perf_event; 0 with callgrind (counted there) or none.
  uint64_t end_frame();
  // A read of the hardware counter failed: the counts are not to be used.
  bool failed() const { return failed_; }

 private:
  InstructionSource source_ = InstructionSource::None;
  int fd_ = -1;
  uint64_t start_ = 0;
  bool failed_ = false;
  std::string why_none_ = "not asked for";
};

// Whether this binary was built with a sanitizer (ASan, TSan): valgrind
// cannot run it, so callgrind counts nothing of it.
bool sanitizer_build();

// Whether this process can count with perf_event (a hardware counter opens);
// "" when it can, else why not ("perf_event_open: No such file or directory").
std::string perf_event_problem();

// Callgrind's output file: the instructions it collected ("totals:" or
// "summary:" of the Ir event); nullopt-like 0 with `problem` set when the file
// cannot be read or holds no total.
uint64_t callgrind_totals(const std::string& path, std::string& problem);

}  // namespace crowdprof

#include "measuring/instruction_counter.h"

#include <linux/perf_event.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define CROWDPROF_HAVE_CALLGRIND 1
#else
#define CROWDPROF_HAVE_CALLGRIND 0
#endif

namespace crowdprof {

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define CROWDPROF_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define CROWDPROF_SANITIZED 1
#endif

bool sanitizer_build() {
#ifdef CROWDPROF_SANITIZED
  return true;
#else
  return false;
#endif
}

const char* instruction_source_name(InstructionSource source) {
  switch (source) {
    case InstructionSource::PerfEvent:
      return "perf_event";
    case InstructionSource::Callgrind:
      return "callgrind";
    case InstructionSource::None:
      break;
  }
  return "none";
}

namespace {

bool under_callgrind() {
#if CROWDPROF_HAVE_CALLGRIND
  return RUNNING_ON_VALGRIND != 0;
#else
  return false;
#endif
}

void toggle_callgrind() {
#if CROWDPROF_HAVE_CALLGRIND
  CALLGRIND_TOGGLE_COLLECT;
#endif
}

// This thread's user-space instructions, counting from now on.
int open_instructions(std::string& problem) {
  perf_event_attr attr{};
  attr.type = PERF_TYPE_HARDWARE;
  attr.size = sizeof attr;
  attr.config = PERF_COUNT_HW_INSTRUCTIONS;
  attr.exclude_kernel = 1;  // the frame's own work, not the system's
  attr.exclude_hv = 1;
  long fd = ::syscall(SYS_perf_event_open, &attr, 0 /* this thread */, -1 /* any CPU */, -1, 0);
  if (fd < 0) problem = std::string("perf_event_open: ") + std::strerror(errno);
  return static_cast<int>(fd);
}

bool read_count(int fd, uint64_t& count) {
  return ::read(fd, &count, sizeof count) == static_cast<ssize_t>(sizeof count);
}

}  // namespace

InstructionCounter::InstructionCounter(InstructionCounter&& other) noexcept {
  *this = std::move(other);
}

InstructionCounter& InstructionCounter::operator=(InstructionCounter&& other) noexcept {
  std::swap(source_, other.source_);
  std::swap(fd_, other.fd_);
  std::swap(start_, other.start_);
  std::swap(failed_, other.failed_);
  std::swap(why_none_, other.why_none_);
  return *this;
}

InstructionCounter::~InstructionCounter() {
  if (fd_ >= 0) ::close(fd_);
}

InstructionCounter InstructionCounter::open() {
  InstructionCounter counter;
  if (under_callgrind()) {
    counter.source_ = InstructionSource::Callgrind;
    return counter;
  }
  counter.fd_ = open_instructions(counter.why_none_);
  if (counter.fd_ >= 0) counter.source_ = InstructionSource::PerfEvent;
  return counter;
}

void InstructionCounter::begin_frame() {
  if (source_ == InstructionSource::Callgrind) toggle_callgrind();
  if (source_ == InstructionSource::PerfEvent && !read_count(fd_, start_)) failed_ = true;
}

uint64_t InstructionCounter::end_frame() {
  if (source_ == InstructionSource::Callgrind) toggle_callgrind();
  uint64_t now = 0;
  if (source_ != InstructionSource::PerfEvent) return 0;
  if (!read_count(fd_, now) || now < start_) {
    failed_ = true;
    return 0;
  }
  return now - start_;
}

std::string perf_event_problem() {
  std::string problem;
  int fd = open_instructions(problem);
  if (fd >= 0) ::close(fd);
  return problem;
}

uint64_t callgrind_totals(const std::string& path, std::string& problem) {
  std::ifstream in(path);
  if (!in) {
    problem = path + ": callgrind wrote no output";
    return 0;
  }
  // "events: Ir ..." names the columns; "totals:" (or "summary:") holds them.
  std::string line, events;
  uint64_t total = 0;
  bool found = false;
  while (std::getline(in, line)) {
    if (line.rfind("events:", 0) == 0) events = line.substr(7);
    if (line.rfind("totals:", 0) == 0 || line.rfind("summary:", 0) == 0) {
      std::istringstream values(line.substr(line.find(':') + 1));
      std::istringstream names(events);
      std::string name;
      uint64_t value = 0;
      while (names >> name && values >> value)
        if (name == "Ir") total = value, found = true;
    }
  }
  if (!found) problem = path + ": no Ir total in callgrind's output";
  return total;
}

}  // namespace crowdprof

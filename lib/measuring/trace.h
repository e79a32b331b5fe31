// A recorder of timed spans, written as Chrome trace-event JSON (opens in
// Perfetto and chrome://tracing): one span per stage per frame on the main
// thread and one per task on each worker thread, so the balance of the threaded
// mode can be seen. A bench without a tracer records nothing and pays nothing.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/errors.h"

namespace crowdprof {

struct TraceArg {
  std::string_view key;  // static storage, e.g. "frame"
  int64_t value = 0;
};

// One complete ("ph":"X") event. Names and keys must outlive the tracer (string
// literals, category_name()): recording copies no strings.
struct TraceSpan {
  std::string_view name, category;
  int64_t start_ns = 0, duration_ns = 0;  // since the tracer's epoch
  int pid = 1;
  uint32_t tid = 0;
  TraceArg args[2]{};
  uint8_t arg_count = 0;
};

// A trace keeps at most this many spans, about 100 MB of JSON (a span is about
// 100 bytes written): a long run would otherwise write gigabytes. Spans past it
// are counted, not kept, and the trace says how many were dropped.
inline constexpr size_t kMaxTraceSpans = 1'000'000;

// What to say before a traced run of `frames` frames (warm-up included) that
// will pass `max_spans`: the main thread alone records a span per frame and one
// per stage, so the estimate is low, never high. Empty when it fits.
SettingText trace_length_warning(size_t frames, size_t max_spans);

class Tracer {
 public:
  using Clock = std::chrono::steady_clock;

  // The constructing thread becomes tid 1, "main"; other threads get 2, 3, ...
  // in the order they first record, named "worker 2", "worker 3", ...
  explicit Tracer(size_t max_spans = kMaxTraceSpans);
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // Records [start, end) on the calling thread; safe from any thread. Only the
  // first recording of a thread takes a lock. Past max_spans(), only counts.
  void span(std::string_view name, std::string_view category, Clock::time_point start, Clock::time_point end, int pid,
            std::initializer_list<TraceArg> args = {});

  // Names a process track (Perfetto shows it as the group's title).
  void name_process(int pid, std::string name);

  size_t max_spans() const { return max_spans_; }
  // Spans not kept because max_spans() were already kept.
  size_t dropped() const;

  // Spans recorded so far, by thread, in the order each thread recorded them.
  std::vector<TraceSpan> spans() const;

  // {"traceEvents": [...], "displayTimeUnit": "ms"}: metadata naming every
  // process and thread, then the spans with ts and dur in microseconds; and,
  // when spans were dropped, "crowdprof": {"dropped_spans", "max_spans"}.
  nlohmann::json to_json() const;
  void write(std::ostream& out) const;

 private:
  struct ThreadBuffer {
    std::thread::id thread;
    uint32_t tid = 0;
    std::vector<TraceSpan> spans;
  };
  ThreadBuffer& buffer_for_this_thread();
  template <typename Emit>
  void for_each_event(Emit emit) const;

  const size_t max_spans_;
  std::atomic<size_t> offered_{0};  // spans offered to span(), kept or not
  const uint64_t serial_;           // tells a thread's cached buffer from another tracer's
  const Clock::time_point epoch_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<ThreadBuffer>> buffers_;
  std::vector<std::pair<int, std::string>> processes_;
};

}  // namespace crowdprof

#include "measuring/trace.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <set>

#include "measuring/category_clock.h"

namespace crowdprof {

namespace {

std::atomic<uint64_t> next_serial{1};

// Each thread remembers its buffer in the tracer it last recorded into, so a
// span costs a clock read and a push_back, not a lock.
struct CachedBuffer {
  uint64_t serial = 0;
  void* buffer = nullptr;
};
thread_local CachedBuffer cached;

double microseconds(int64_t ns) {
  return static_cast<double>(ns) / 1000.0;
}

}  // namespace

SettingText trace_length_warning(size_t frames, size_t max_spans) {
  constexpr size_t kMainSpansPerFrame = 1 + kCategoryCount;
  if (frames <= max_spans / kMainSpansPerFrame) return "";
  return "{trace} keeps " + std::to_string(max_spans) + " spans, about the first " +
         std::to_string(max_spans / kMainSpansPerFrame) + " of these " + std::to_string(frames) +
         " frames; later spans are counted, not written";
}

Tracer::Tracer(size_t max_spans) : max_spans_(max_spans), serial_(next_serial.fetch_add(1)), epoch_(Clock::now()) {
  buffer_for_this_thread();  // the constructing thread is tid 1
}

Tracer::ThreadBuffer& Tracer::buffer_for_this_thread() {
  if (cached.serial == serial_) return *static_cast<ThreadBuffer*>(cached.buffer);
  std::lock_guard lock(mutex_);
  std::thread::id me = std::this_thread::get_id();
  ThreadBuffer* found = nullptr;
  for (auto& buffer : buffers_)
    if (buffer->thread == me) found = buffer.get();
  if (!found) {
    buffers_.push_back(std::make_unique<ThreadBuffer>());
    found = buffers_.back().get();
    found->thread = me;
    found->tid = static_cast<uint32_t>(buffers_.size());
    found->spans.reserve(1024);
  }
  cached = {serial_, found};
  return *found;
}

void Tracer::span(std::string_view name, std::string_view category, Clock::time_point start, Clock::time_point end,
                  int pid, std::initializer_list<TraceArg> args) {
  if (offered_.fetch_add(1, std::memory_order_relaxed) >= max_spans_) return;
  ThreadBuffer& buffer = buffer_for_this_thread();
  TraceSpan s;
  s.name = name;
  s.category = category;
  s.start_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(start - epoch_).count();
  s.duration_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(end - start).count();
  s.pid = pid;
  s.tid = buffer.tid;
  for (const TraceArg& arg : args)
    if (s.arg_count < 2) s.args[s.arg_count++] = arg;
  buffer.spans.push_back(s);
}

size_t Tracer::dropped() const {
  size_t offered = offered_.load(std::memory_order_relaxed);
  return offered > max_spans_ ? offered - max_spans_ : 0;
}

void Tracer::name_process(int pid, std::string name) {
  std::lock_guard lock(mutex_);
  for (auto& [id, existing] : processes_)
    if (id == pid) {
      existing = std::move(name);
      return;
    }
  processes_.emplace_back(pid, std::move(name));
}

std::vector<TraceSpan> Tracer::spans() const {
  std::lock_guard lock(mutex_);
  std::vector<TraceSpan> all;
  for (const auto& buffer : buffers_) all.insert(all.end(), buffer->spans.begin(), buffer->spans.end());
  return all;
}

// The events of a trace: metadata naming every process and thread, then the
// spans by start time. `emit` takes each event in turn, so write() can stream a
// large trace without holding all of it as JSON.
template <typename Emit>
void Tracer::for_each_event(Emit emit) const {
  std::vector<TraceSpan> all = spans();
  std::sort(all.begin(), all.end(), [](const TraceSpan& a, const TraceSpan& b) {
    return a.start_ns != b.start_ns ? a.start_ns < b.start_ns : a.duration_ns > b.duration_ns;
  });
  // Every (pid, tid) that has a span gets a thread name, every pid a process name.
  std::set<std::pair<int, uint32_t>> threads;
  std::map<int, std::string> processes;
  for (const TraceSpan& s : all) {
    threads.insert({s.pid, s.tid});
    processes.emplace(s.pid, "crowdprof");
  }
  {
    std::lock_guard lock(mutex_);
    for (const auto& [pid, name] : processes_) processes[pid] = name;
  }
  for (const auto& [pid, name] : processes) {
    emit(nlohmann::json{{"name", "process_name"}, {"ph", "M"}, {"pid", pid}, {"tid", 0}, {"args", {{"name", name}}}});
    emit(nlohmann::json{
        {"name", "process_sort_index"}, {"ph", "M"}, {"pid", pid}, {"tid", 0}, {"args", {{"sort_index", pid}}}});
  }
  for (const auto& [pid, tid] : threads) {
    std::string name = tid == 1 ? "main" : "worker " + std::to_string(tid);
    emit(nlohmann::json{{"name", "thread_name"}, {"ph", "M"}, {"pid", pid}, {"tid", tid}, {"args", {{"name", name}}}});
    emit(nlohmann::json{
        {"name", "thread_sort_index"}, {"ph", "M"}, {"pid", pid}, {"tid", tid}, {"args", {{"sort_index", tid}}}});
  }
  for (const TraceSpan& s : all) {
    nlohmann::json event = {{"name", s.name},
                            {"cat", s.category},
                            {"ph", "X"},
                            {"ts", microseconds(s.start_ns)},
                            {"dur", microseconds(s.duration_ns)},
                            {"pid", s.pid},
                            {"tid", s.tid}};
    for (uint8_t i = 0; i < s.arg_count; ++i) event["args"][std::string(s.args[i].key)] = s.args[i].value;
    emit(std::move(event));
  }
}

nlohmann::json Tracer::to_json() const {
  nlohmann::json events = nlohmann::json::array();
  for_each_event([&](nlohmann::json event) { events.push_back(std::move(event)); });
  nlohmann::json doc = {{"traceEvents", std::move(events)}, {"displayTimeUnit", "ms"}};
  if (dropped()) doc["crowdprof"] = {{"dropped_spans", dropped()}, {"max_spans", max_spans_}};
  return doc;
}

void Tracer::write(std::ostream& out) const {
  // One event per line: readable, and diff-friendly, without the bulk of
  // dump(2). Streamed: a million spans as one JSON value would take a gigabyte.
  out << "{\"displayTimeUnit\":\"ms\",";
  if (dropped())
    out << "\"crowdprof\":" << nlohmann::json{{"dropped_spans", dropped()}, {"max_spans", max_spans_}}.dump() << ",";
  out << "\"traceEvents\":[";
  bool first = true;
  for_each_event([&](const nlohmann::json& event) {
    out << (first ? "\n" : ",\n") << event.dump();
    first = false;
  });
  out << "\n]}\n";
}

}  // namespace crowdprof

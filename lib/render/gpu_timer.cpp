#include "render/gpu_timer.h"

#include <algorithm>

namespace {

// ARB_pipeline_statistics_query's targets (GL 4.6), in PipelineStat's order.
constexpr GLenum kStatTargets[] = {0x82EE /* VERTICES_SUBMITTED */, 0x82EF /* PRIMITIVES_SUBMITTED */,
                                   0x82F0 /* VERTEX_SHADER_INVOCATIONS */, 0x82F4 /* FRAGMENT_SHADER_INVOCATIONS */,
                                   0x82F5 /* COMPUTE_SHADER_INVOCATIONS */};

}  // namespace

namespace crowdprof {

GpuTimer::~GpuTimer() {
  for (Slot& slot : slots_) {
    if (slot.query) glDeleteQueries(1, &slot.query);
    glDeleteQueries(static_cast<GLsizei>(slot.stamps.size()), slot.stamps.data());
    glDeleteQueries(static_cast<GLsizei>(slot.stats.size()), slot.stats.data());
  }
}

void GpuTimer::measure_resolution() {
  // The clock's tick: the smallest step between two readings that differ.
  GLint64 last = 0, tick = 0;
  glGetInteger64v(GL_TIMESTAMP, &last);
  for (int read = 0, steps = 0; read < 20000 && steps < 32; ++read) {
    GLint64 now = 0;
    glGetInteger64v(GL_TIMESTAMP, &now);
    if (now <= last) continue;
    tick = tick == 0 ? now - last : std::min(tick, now - last);
    last = now;
    ++steps;
  }
  // The floor: what a query around no work reads.
  GLuint query = 0;
  glGenQueries(1, &query);
  GLuint64 floor = 0;
  for (int i = 0; i < 8; ++i) {
    glBeginQuery(GL_TIME_ELAPSED, query);
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    floor = std::max(floor, ns);
  }
  glDeleteQueries(1, &query);
  resolution_ms_ =
      static_cast<double>(std::max<uint64_t>(static_cast<uint64_t>(std::max<GLint64>(tick, 1)), floor)) * 1e-6;
}

void GpuTimer::begin(const void* owner, uint64_t frame, bool statistics) {
  if (resolution_ms_ < 0) measure_resolution();  // before any query of ours is active
  auto free = std::find_if(slots_.begin(), slots_.end(), [](const Slot& s) { return s.state == State::Free; });
  if (free == slots_.end()) {
    // Queries nobody took: drop the oldest, waiting for its result so that
    // its query object can be begun again.
    free =
        std::min_element(slots_.begin(), slots_.end(), [](const Slot& a, const Slot& b) { return a.order < b.order; });
    GLuint64 ns = 0;
    glGetQueryObjectui64v(free->query, GL_QUERY_RESULT, &ns);
  }
  Slot& slot = *free;
  if (!slot.query) glGenQueries(1, &slot.query);
  slot.owner = owner;
  slot.frame = frame;
  slot.order = next_order_++;
  slot.state = State::Pending;
  slot.statistics = statistics;
  slot.passes.clear();
  slot.stamps_used = 0;
  glBeginQuery(GL_TIME_ELAPSED, slot.query);
  active_ = &slot;
}

GLuint GpuTimer::next_stamp(Slot& slot) {
  if (slot.stamps_used == slot.stamps.size()) {
    slot.stamps.push_back(0);
    glGenQueries(1, &slot.stamps.back());
  }
  GLuint stamp = slot.stamps[slot.stamps_used++];
  glQueryCounter(stamp, GL_TIMESTAMP);
  return stamp;
}

void GpuTimer::close_segment(Slot& slot) {
  if (slot.passes.empty() || !slot.statistics) return;
  for (GLenum target : kStatTargets) glEndQuery(target);
}

void GpuTimer::mark(GpuPass pass) {
  if (!active_) return;
  Slot& slot = *active_;
  // Back to back segments of one pass are one segment.
  if (!slot.passes.empty() && slot.passes.back() == pass) return;
  close_segment(slot);
  next_stamp(slot);
  slot.passes.push_back(pass);
  if (!slot.statistics) return;
  size_t first = kPipelineStatCount * (slot.passes.size() - 1);
  if (slot.stats.size() < first + kPipelineStatCount) {
    slot.stats.resize(first + kPipelineStatCount, 0);
    glGenQueries(static_cast<GLsizei>(kPipelineStatCount), &slot.stats[first]);
  }
  for (size_t s = 0; s < kPipelineStatCount; ++s) glBeginQuery(kStatTargets[s], slot.stats[first + s]);
}

void GpuTimer::end() {
  if (!active_) return;
  close_segment(*active_);
  if (!active_->passes.empty()) next_stamp(*active_);
  glEndQuery(GL_TIME_ELAPSED);
  active_ = nullptr;
}

GpuPassFigures GpuTimer::read_passes(Slot& slot) {
  GpuPassFigures f;
  if (slot.passes.empty()) return f;
  f.ms.fill(0);
  if (slot.statistics)
    for (auto& pass : f.stats) pass.fill(0);
  GLuint64 start = 0;
  glGetQueryObjectui64v(slot.stamps[0], GL_QUERY_RESULT, &start);
  for (size_t i = 0; i < slot.passes.size(); ++i) {
    GLuint64 stop = 0;
    glGetQueryObjectui64v(slot.stamps[i + 1], GL_QUERY_RESULT, &stop);
    auto p = static_cast<size_t>(slot.passes[i]);
    f.ms[p] += static_cast<double>(stop - std::min(start, stop)) * 1e-6;
    start = stop;
    if (!slot.statistics) continue;
    for (size_t s = 0; s < kPipelineStatCount; ++s) {
      GLuint64 count = 0;
      glGetQueryObjectui64v(slot.stats[kPipelineStatCount * i + s], GL_QUERY_RESULT, &count);
      f.stats[p][s] += static_cast<double>(count);
    }
  }
  return f;
}

size_t GpuTimer::take(const void* owner, uint64_t frame, std::span<GpuTime> out, bool wait) {
  // Oldest first, so that a caller sees its frames in order.
  std::array<Slot*, kRing> mine{};
  size_t count = 0;
  for (Slot& slot : slots_)
    if (slot.state != State::Free && slot.owner == owner && &slot != active_ && (wait || slot.frame < frame))
      mine[count++] = &slot;
  // Insertion sort of at most kRing slots (std::sort here draws a false
  // -Warray-bounds from GCC 12, which assumes 16 elements for small sorts).
  for (size_t i = 1; i < count; ++i)
    for (size_t j = i; j > 0 && mine[j]->order < mine[j - 1]->order; --j) std::swap(mine[j], mine[j - 1]);
  size_t written = 0;
  for (size_t i = 0; i < count && written < out.size(); ++i) {
    Slot& slot = *mine[i];
    GLint available = 0;
    if (!wait) glGetQueryObjectiv(slot.query, GL_QUERY_RESULT_AVAILABLE, &available);
    if (!wait && !available) break;  // later ones are not ready either
    GLuint64 ns = 0;
    glGetQueryObjectui64v(slot.query, GL_QUERY_RESULT, &ns);
    out[written++] = {slot.frame, static_cast<double>(ns) * 1e-6, read_passes(slot)};
    slot.state = State::Free;
    slot.owner = nullptr;
  }
  return written;
}

}  // namespace crowdprof

// GPU time per frame from GL timer queries (GL_TIME_ELAPSED), split by pass
// with a GL_TIMESTAMP at each boundary (mark()), and each pass's pipeline
// statistics where the GL has them. A query's result
// is read a frame or more after its frame, when the GL says it is available,
// so that reading it never stalls the pipeline: the queries live in a small
// ring, each tagged with the frame (and the bench, as one renderer draws every
// mode of a compare) it timed.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <vector>

#include "frame/frame_renderer.h"
#include "measuring/gpu_passes.h"
#include "render/gl.h"

namespace crowdprof {

class GpuTimer {
 public:
  // Frames in flight at most; more than a GL keeps queued between two finishes.
  static constexpr size_t kRing = kGpuTimesInFlight;

  GpuTimer() = default;
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // Starts timing frame `frame` of `owner`. When every slot still holds a
  // query nobody took, the oldest is dropped (its frame shows no GPU time).
  // With `statistics`, each pass also counts ARB_pipeline_statistics_query's
  // figures (the GL must have it).
  void begin(const void* owner, uint64_t frame, bool statistics = false);
  // From here to the next mark() or end(), the GPU works on `pass`. A pass may
  // be marked many times a frame (compute skinning's batches): its segments add
  // up. Work before the first mark counts in the frame, in no pass.
  void mark(GpuPass pass);
  // Ends the query begun last.
  void end();
  // Writes the finished results of `owner`'s frames before `frame` (at most
  // out.size(), oldest first) and frees their slots; returns how many. With
  // `wait`, every query of `owner`'s, waiting for those in flight.
  size_t take(const void* owner, uint64_t frame, std::span<GpuTime> out, bool wait);

  // The smallest GPU time this timer can tell from nothing, in ms, measured on
  // the first begin(): the larger of the step GL_TIMESTAMP takes between two
  // reads and what an empty GL_TIME_ELAPSED query reads. A frame's time below
  // it is not a measurement (llvmpipe's tiny frames read 0.00 ms). 0 before.
  double resolution_ms() const { return resolution_ms_ > 0 ? resolution_ms_ : 0; }

 private:
  void measure_resolution();
  enum class State : uint8_t { Free, Pending };
  // The pass each segment timed; stamps[i] starts segment i (the last one
  // ends the frame); stats[kPipelineStatCount * i + s] counts statistic s.
  struct Slot {
    GLuint query = 0;
    const void* owner = nullptr;
    uint64_t frame = 0, order = 0;
    State state = State::Free;
    bool statistics = false;
    std::vector<GpuPass> passes;
    std::vector<GLuint> stamps, stats;  // query objects, kept for the slot's next frames
    size_t stamps_used = 0;
  };
  void close_segment(Slot& slot);
  GLuint next_stamp(Slot& slot);
  GpuPassFigures read_passes(Slot& slot);
  std::array<Slot, kRing> slots_{};
  uint64_t next_order_ = 0;
  Slot* active_ = nullptr;
  double resolution_ms_ = -1;  // < 0: not measured yet
};

}  // namespace crowdprof

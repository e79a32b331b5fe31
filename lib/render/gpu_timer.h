// GPU time per frame from GL timer queries (GL_TIME_ELAPSED). A query's result
// is read a frame or more after its frame, when the GL says it is available,
// so that reading it never stalls the pipeline: the queries live in a small
// ring, each tagged with the frame (and the bench, as one renderer draws every
// mode of a compare) it timed.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "frame/frame_renderer.h"
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
  void begin(const void* owner, uint64_t frame);
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
  struct Slot {
    GLuint query = 0;
    const void* owner = nullptr;
    uint64_t frame = 0, order = 0;
    State state = State::Free;
  };
  std::array<Slot, kRing> slots_{};
  uint64_t next_order_ = 0;
  Slot* active_ = nullptr;
  double resolution_ms_ = -1;  // < 0: not measured yet
};

}  // namespace crowdprof

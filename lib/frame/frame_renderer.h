// What the frame loop asks of a renderer (lib/render/ implements it with GL).
// The frame loop knows nothing of GL: it calls these in the BGE's stages, and
// the renderer draws from the FrameView it is given, calling nothing back.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "frame/frame_view.h"
#include "base/modes.h"
#include "measuring/counters.h"
#include "result/result.h"

namespace crowdprof {

// The GPU's time for one frame of a bench, from a timer query read later.
struct GpuTime {
  uint64_t frame = 0;  // the frame's number (FrameView::frame when it was drawn)
  double ms = 0;
  GpuPassFigures passes;  // the same time by pass, when the GL could split it
};
// Frames whose GPU time may be awaited at once: a renderer keeps this many queries.
inline constexpr size_t kGpuTimesInFlight = 8;

class FrameRenderer {
 public:
  virtual ~FrameRenderer() = default;

  // Joints a character may have for the GPU to skin it in `mode` (the vertex
  // shader's bone array with uniform palettes); a character with more is
  // skinned on the CPU instead.
  virtual size_t max_gpu_joints(const ModeSwitches& mode) const = 0;

  // Throws (std::runtime_error: exit 4), before any frame, when `mode` needs
  // something the GL lacks, naming it (e.g. shader storage buffers in the
  // vertex stage for --palettes buffer).
  virtual void require(const ModeSwitches& mode) const = 0;

  // At load, from the bench's constructor (its view complete, frame 0 not
  // run): upload what the mode needs and never changes (baked tables, the GPU
  // cull pass's copies) and make the buffers its frames fill. Throws GlUnavailable
  // (gl_errors.h) when the context lacks a feature the mode needs, naming it.
  virtual void prepare(const FrameView& view) = 0;

  // Bytes the renderer holds on the GPU for animation and skinning data: baked
  // tables, palette and instance buffers, compute output buffers
  // (meshes and index buffers not counted).
  virtual uint64_t animation_gpu_bytes() const = 0;

  // The GPU's memory as the GL reports it (when the renderer was made).
  virtual GpuMemoryRecord gpu_memory() const = 0;

  // Rasterizer stage: send this frame's data and submit one draw per copy on
  // screen (or per character kind, drawn instanced): skinned vertices of the
  // copies skinned on the CPU, skinning matrices (or baked positions) of the
  // others. Adds to counters.bytes_uploaded and counters.draw_calls. Throws
  // (std::runtime_error) on a GL error, naming it and the stage.
  virtual void draw(const FrameView& view, Counters& counters) = 0;

  // GPU Latency stage: wait until the frame is drawn (the BGE's SwapBuffers).
  virtual void finish() = 0;

  // After finish(), with frustum gpu: how many copies of each character the
  // GPU's cull pass found on screen in `view`'s frame at each mesh level, into
  // `per_group` (character k's level l at k x kMeshLevels + l; level 0 alone
  // without mesh LOD). False (and nothing written) when the frame was not
  // culled on the GPU.
  virtual bool gpu_visible_counts(const FrameView& view, std::span<uint64_t> per_group) const {
    (void)view;
    (void)per_group;
    return false;
  }

  // Empty when draw() times each frame on the GPU (GL timer queries), else
  // why not, for the report ("... has no GL_TIME_ELAPSED timer").
  virtual std::string gpu_timing_missing() const = 0;
  // Empty when each pass's GPU time comes with its pipeline statistics, else why not.
  virtual std::string pipeline_statistics_missing() const = 0;
  // The GPU times of the frames drawn from `owner` (a view) before `frame` whose queries have
  // finished (never waiting for one, so never stalling), oldest first, at most
  // out.size(); with `wait`, every frame still in flight, waiting for them.
  // Returns how many were written.
  virtual size_t take_gpu_times(const FrameView* owner, uint64_t frame, std::span<GpuTime> out, bool wait) = 0;
  // The smallest GPU time the timer tells from nothing, in ms (GpuTimer::
  // resolution_ms); 0 when not known.
  virtual double gpu_timer_resolution_ms() const { return 0; }
};

}  // namespace crowdprof

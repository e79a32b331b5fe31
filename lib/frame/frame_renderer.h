// What the frame loop asks of a renderer (lib/render/ implements it with GL).
// The frame loop knows nothing of GL: it calls these in the BGE's stages.
#pragma once

#include <cstddef>

#include "frame/modes.h"
#include "profile/counters.h"

namespace crowdprof {

class CrowdBench;

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

  // Rasterizer stage: send this frame's data and submit one draw per copy on
  // screen (or per character kind, drawn instanced): skinned vertices when
  // bench.gpu_skinned() is false, else skinning matrices. Adds to counters.bytes_uploaded and counters.draw_calls. Throws
  // (std::runtime_error) on a GL error, naming it and the stage.
  virtual void draw(const CrowdBench& bench, Counters& counters) = 0;

  // GPU Latency stage: wait until the frame is drawn (the BGE's SwapBuffers).
  virtual void finish() = 0;
};

}  // namespace crowdprof

// The draws of the crowd a frame makes (modes.h's passes): a depth prepass
// into the frame's own depth buffer, shadow cascades each into a depth map of
// its own, then colour. The prepass and the cascades draw with each
// technique's colour program and colour writes masked off; the colour pass
// after a prepass tests depth with LEQUAL, so it shades each pixel once and
// the image is the one without passes.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "frame/frame_view.h"
#include "measuring/gpu_passes.h"
#include "render/gl.h"

namespace crowdprof {

struct DrawPass {
  GpuPass kind = GpuPass::Colour;
  glm::mat4 view_projection{1.0f};
  size_t cascade = 0;  // kind Shadows: which
  bool colour() const { return kind == GpuPass::Colour; }
};

// The frame's draw passes, in order.
std::vector<DrawPass> draw_passes(const FrameView& view);

// Depth-only targets, one per shadow cascade.
class ShadowMaps {
 public:
  static constexpr int kSize = 2048;  // texels each way, a common cascade size

  ShadowMaps() = default;
  ~ShadowMaps();
  ShadowMaps(const ShadowMaps&) = delete;
  ShadowMaps& operator=(const ShadowMaps&) = delete;

  // Makes depth maps until there are `count`. Throws GlError when the driver
  // cannot complete one.
  void reserve(size_t count);
  // Binds cascade `c`'s map for drawing, with its viewport, and clears it.
  void bind_and_clear(size_t c) const;
  size_t count() const { return framebuffers_.size(); }
  uint64_t gpu_bytes() const { return count() * uint64_t{kSize} * kSize * 4; }

 private:
  std::vector<GLuint> framebuffers_, textures_;
};

}  // namespace crowdprof

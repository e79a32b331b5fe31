// Skinning in the vertex shader with every copy's palette in one shader
// storage buffer (mode buffer, --palettes buffer): no bone limit but the
// storage block's size, one upload a frame, then a draw per copy that tells
// the shader where its palette starts.
#pragma once

#include <cstdint>
#include <vector>

#include "frame/frame_view.h"
#include "render/character_meshes.h"
#include "render/gl_features.h"
#include "render/gpu_frame_buffers.h"
#include "render/techniques/technique.h"

namespace crowdprof {

// The run of records a copy's palette goes in: one per character and mesh
// level (character k's level l is run k x kMeshLevels + l), so that an
// instanced draw takes copies of one level.
inline size_t draw_group(const FrameView& view, size_t copy) {
  return view.kind[copy] * kMeshLevels + view.level_of(copy);
}

// This frame's palettes (and instance records) of the copies on screen that
// the vertex shader skins from a palette buffer, per character and mesh level
// (draw_group), into `buffers`, sent to the GPU (records too when `instanced`). Room is made for
// every such copy, on screen or not, so that the buffers never grow while the
// crowd turns. Returns the bytes sent. Throws GlUnavailable when the palettes
// exceed one storage block (`max_block_bytes`).
// `on_screen` is scratch, kept by the caller so that frames allocate nothing.
SentBytes send_palettes(const FrameView& view, const CharacterMeshes& meshes, GpuFrameBuffers& buffers,
                        std::vector<uint32_t>& on_screen, const GlFeatures& gl, bool instanced);

class BufferPalette final : public Technique {
 public:
  // Uploads every character's rest mesh. Needs vertex-stage storage buffers.
  BufferPalette(CharacterMeshes& meshes, const GlFeatures& gl);

  void upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) override;
  void draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) override;

 private:
  GlFeatures gl_;
  GlProgram program_;
  GLint model_ = -1, colour_ = -1, base_ = -1;
  GpuFrameBuffers buffers_;
  std::vector<uint32_t> on_screen_;  // scratch: per draw group, copies on screen
  std::vector<uint32_t> next_;       // scratch: per draw group, the next record to draw
};

// shaders/buffer_skin.vert with shaders/instances.glsl ahead of it (and, when
// `instanced`, the placements as uniform pages of `gl`'s blocks).
std::vector<ShaderStage> buffer_palette_stages(bool instanced, const GlFeatures& gl);

}  // namespace crowdprof

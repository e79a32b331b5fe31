// The buffer palettes drawn with one instanced draw per character (mode
// instanced, --draw instanced): each instance reads its model matrix, colour
// and palette offset from a record (render/gpu_frame_buffers.h) fetched as
// per-instance vertex attributes.
#pragma once

#include <cstdint>
#include <vector>

#include "render/character_meshes.h"
#include "render/gl_features.h"
#include "render/gpu_frame_buffers.h"
#include "render/techniques/technique.h"

namespace crowdprof {

class Instanced final : public Technique {
 public:
  // Uploads every character's rest mesh. Needs vertex-stage storage buffers.
  Instanced(CharacterMeshes& meshes, const GlFeatures& gl);

  void upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) override;
  void draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) override;

  // Bytes one copy of `mesh` costs to send: its palette's rows and its record.
  static uint64_t bytes_per_copy(const CharacterMesh& mesh);

 private:
  GlFeatures gl_;
  GlProgram program_;
  GpuFrameBuffers buffers_;
  std::vector<uint32_t> on_screen_;  // scratch: per character, copies on screen
};

}  // namespace crowdprof

// Skinning in the vertex shader, the thesis's 4.4 (mode hwskin): the rest
// mesh goes up once, and each copy's palette is sent as a uniform array before
// its draw. The array holds at most the bone limit (gpu_joint_limit): a
// character over it is skinned on the CPU instead.
#pragma once

#include <cstdint>
#include <vector>

#include "render/character_meshes.h"
#include "render/techniques/technique.h"

namespace crowdprof {

class UniformPalette final : public Technique {
 public:
  // Uploads the rest meshes of the characters within `bone_limit` joints.
  UniformPalette(CharacterMeshes& meshes, size_t bone_limit);

  // The copies on screen whose character the mode skins on the GPU from a
  // uniform palette. Throws GlError for one over the bone limit.
  void upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) override;
  void draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) override;

  // Bytes one copy of `mesh` costs to send: its palette's rows and model.
  static uint64_t bytes_per_copy(const CharacterMesh& mesh);

 private:
  size_t bone_limit_;
  GlProgram program_;
  GLint model_ = -1, colour_ = -1, bones_ = -1;
  std::vector<glm::vec4> rows_;  // scratch: one copy's 3 x joints rows
};

}  // namespace crowdprof

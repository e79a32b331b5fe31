// Skinning in a compute pass (mode compute, --skinning compute): each batch of
// copies' palettes goes up, a compute shader (shaders/skin.comp) skins every
// vertex of every copy into a storage buffer, and the draws read that buffer
// as vertex attributes with the plain lit program.
#pragma once

#include <cstdint>
#include <vector>

#include "render/character_meshes.h"
#include "render/techniques/technique.h"

namespace crowdprof {

class ComputeSkinning final : public Technique {
 public:
  ComputeSkinning();
  ~ComputeSkinning() override;

  // Uploads the rest mesh of each character the bench skins by compute and
  // sizes the batch buffers for its crowd.
  void prepare(const FrameView& view, const CharacterMeshes& meshes);
  // GPU storage held: rest meshes and batch buffers.
  uint64_t gpu_bytes() const { return gpu_bytes_; }

  // The copies on screen whose character the bench skins by compute.
  void draw(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) override;

 private:
  void draw_kind(const FrameView& view, const CharacterMesh& mesh, size_t kind, Counters& counters);

  GlProgram skin_program_, draw_program_;
  GLint vertex_count_ = -1, joint_count_ = -1, model_ = -1, colour_ = -1;
  GLuint vao_ = 0, bones_ = 0, skinned_ = 0;
  std::vector<GLuint> rest_storage_;  // per character: the rest mesh, 64 bytes a vertex (0: none)
  size_t batch_ = 0, vertices_ = 0, joints_ = 0;  // sizes the batch buffers hold
  uint64_t gpu_bytes_ = 0;
  std::vector<glm::vec4> rows_;      // scratch: a batch's palettes
  std::vector<size_t> copies_;       // scratch: a character's copies on screen
};

}  // namespace crowdprof

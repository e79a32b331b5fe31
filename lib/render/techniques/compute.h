// Skinning in a compute pass (mode compute, --skinning compute): each batch of
// copies' palettes goes up, a compute shader (shaders/skin.comp) skins every
// vertex of every copy into a storage buffer, and the draws read that buffer
// as vertex attributes with the plain lit program.
#pragma once

#include <functional>
#include <span>

#include <cstdint>
#include <vector>

#include "render/character_meshes.h"
#include "render/techniques/technique.h"

namespace crowdprof {

// Called before each segment of compute's work: null before a batch is
// skinned, else the pass its draws go to (the renderer binds its target).
using BeginPass = std::function<void(const DrawPass*)>;

// Not a Technique: its draws must follow the dispatch that skinned their
// batch, so it runs every pass of a batch before skinning the next.
class ComputeSkinning final {
 public:
  ComputeSkinning();
  ~ComputeSkinning();
  ComputeSkinning(const ComputeSkinning&) = delete;
  ComputeSkinning& operator=(const ComputeSkinning&) = delete;

  // Uploads the rest mesh of each character the bench skins by compute and
  // sizes the batch buffers for its crowd.
  void prepare(const FrameView& view, const CharacterMeshes& meshes);
  // GPU storage held: rest meshes and batch buffers.
  uint64_t gpu_bytes() const { return gpu_bytes_; }

  // Skins the copies on screen whose character the bench skins by compute,
  // a batch at a time, and draws each batch in every pass: skinned once
  // whatever the passes. With several passes a batch holds up to 1 GiB of
  // skinned vertices (6,700 copies of the humanoid), so a crowd on screen up
  // to that has its prepass drawn whole before its colour.
  void draw(const FrameView& view, const CharacterMeshes& meshes, std::span<const DrawPass> passes,
            const BeginPass& begin_pass, Counters& counters);

 private:
  void draw_kind(const FrameView& view, const CharacterMesh& mesh, size_t kind, size_t level,
                 std::span<const DrawPass> passes, const BeginPass& begin_pass, Counters& counters);

  GlProgram skin_program_, draw_program_;
  GLint vertex_count_ = -1, joint_count_ = -1, model_ = -1, colour_ = -1;
  GLuint vao_ = 0, bones_ = 0, skinned_ = 0;
  // Per character and mesh level (k x kMeshLevels + level): the rest mesh, 64
  // bytes a vertex (0: none).
  std::vector<GLuint> rest_storage_;
  size_t batch_ = 0, vertices_ = 0, joints_ = 0;  // sizes the batch buffers hold
  uint64_t gpu_bytes_ = 0;
  std::vector<glm::vec4> rows_;  // scratch: a batch's palettes
  std::vector<size_t> copies_;   // scratch: a character's copies on screen
};

}  // namespace crowdprof

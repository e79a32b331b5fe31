// What every technique draws from: each character's index buffer, uploaded
// once, and, for techniques that skin in the vertex shader (uniform or buffer
// palettes, instanced, baked), its rest mesh with joints and weights.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "asset/character.h"
#include "render/gl.h"

namespace crowdprof {

struct CharacterMesh {
  size_t vertices = 0, joints = 0;
  GLsizei index_count = 0;
  GLuint indices = 0;
  // The rest mesh (0 until upload_rest_mesh): positions, normals, joints, weights.
  GLuint rest_buffers[4] = {0, 0, 0, 0};
  GLuint rest_vao = 0;        // the rest mesh and indices, drawn one copy at a time
  GLuint instanced_vao = 0;   // the same, with each instance's record (gpu_frame_buffers.h) from attribute 4
};

class CharacterMeshes {
 public:
  // Uploads each character's indices. A current GL context is needed here and
  // at every call; the characters must outlive this.
  explicit CharacterMeshes(std::span<const Character* const> characters);
  ~CharacterMeshes();
  CharacterMeshes(const CharacterMeshes&) = delete;
  CharacterMeshes& operator=(const CharacterMeshes&) = delete;

  // Uploads character `kind`'s rest mesh once; later calls do nothing.
  void upload_rest_mesh(size_t kind);

  size_t size() const { return meshes_.size(); }
  const CharacterMesh& operator[](size_t kind) const { return meshes_[kind]; }
  const Character& character(size_t kind) const { return *characters_[kind]; }
  size_t max_vertices() const;

 private:
  std::vector<const Character*> characters_;
  std::vector<CharacterMesh> meshes_;
};

}  // namespace crowdprof

// What every technique draws from: each character's index buffer, uploaded
// once, and, for techniques that skin in the vertex shader (uniform or buffer
// palettes, instanced, baked), its rest mesh with joints and weights.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "asset/character.h"
#include "asset/mesh_lod.h"
#include "base/modes.h"
#include "render/gl.h"

namespace crowdprof {

// Where one mesh level is in the buffers a draw binds.
struct MeshLevelDraw {
  GLuint vao = 0;            // rest-mesh VAO (GPU skinning): its vertices at base_vertex
  GLuint instanced_vao = 0;  // the same, with the instance records (CharacterMesh::instanced_vao)
  GLuint indices = 0;        // the index buffer (CPU-skinned draws bind it to their own VAO)
  GLsizei index_count = 0;
  const void* first_index = nullptr;  // byte offset into `indices`
  GLint base_vertex = 0;              // of the level's vertices in the rest buffers (0 for CPU-skinned vertices)
};

struct CharacterMesh {
  size_t vertices = 0, joints = 0;
  GLsizei index_count = 0;
  // The full mesh's triangles twice, one order after the other: the file's,
  // then vertex-cache order (asset/vertex_order.h), at index index_count.
  GLuint indices = 0;
  // The rest mesh (0 until upload_rest_mesh): positions, normals, joints, weights.
  GLuint rest_buffers[4] = {0, 0, 0, 0};
  GLuint rest_vao = 0;       // the rest mesh and indices, drawn one copy at a time
  GLuint instanced_vao = 0;  // the same, with each instance's record (gpu_frame_buffers.h) from attribute 4
  // Mesh LOD (0 until upload_levels): levels 1.. one after another, each with
  // its own indices (counted from its first vertex) and rest vertices.
  struct Levels {
    GLuint indices = 0, rest_buffers[4] = {0, 0, 0, 0}, rest_vao = 0, instanced_vao = 0;
    std::vector<size_t> first_index, first_vertex;  // per level 1..
    // Per level 1..: where its triangles start in vertex-cache order (the same
    // range as first_index for levels built in that order).
    std::vector<size_t> first_optimized;
    std::vector<GLsizei> index_count;
  } levels;

  // How to draw level `level` (0: the full mesh) with its triangles in
  // `order`: from the rest mesh (GPU skinning, `rest` true) or from vertices
  // skinned on the CPU. Levels mesh LOD builds are in vertex-cache order
  // already; a file's own (MSFT_lod) take `order` as the full mesh does.
  MeshLevelDraw draw_of(size_t level, bool rest, IndexOrder order) const;
};

class CharacterMeshes {
 public:
  // Uploads each character's indices, in both orders. A current GL context is needed here and
  // at every call; the characters must outlive this.
  explicit CharacterMeshes(std::span<const Character* const> characters);
  ~CharacterMeshes();
  CharacterMeshes(const CharacterMeshes&) = delete;
  CharacterMeshes& operator=(const CharacterMeshes&) = delete;

  // Uploads character `kind`'s rest mesh once; later calls do nothing.
  void upload_rest_mesh(size_t kind);
  // Mesh LOD: uploads character `kind`'s levels 1.. (indices, rest vertices)
  // once; later calls do nothing. The levels are the same for every bench of
  // one character (build_mesh_lods is deterministic).
  void upload_levels(size_t kind, std::span<const MeshLod> lods);

  size_t size() const { return meshes_.size(); }
  const CharacterMesh& operator[](size_t kind) const { return meshes_[kind]; }
  const Character& character(size_t kind) const { return *characters_[kind]; }
  size_t max_vertices() const;

 private:
  std::vector<const Character*> characters_;
  std::vector<CharacterMesh> meshes_;
};

}  // namespace crowdprof

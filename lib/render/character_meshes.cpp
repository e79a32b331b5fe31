#include "render/character_meshes.h"

#include <algorithm>

#include "asset/vertex_order.h"
#include "render/gpu_frame_buffers.h"
#include "render/techniques/technique.h"

namespace crowdprof {

namespace {

void float_attribute(GLuint index, GLuint buffer, GLint components) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glEnableVertexAttribArray(index);
  glVertexAttribPointer(index, components, GL_FLOAT, GL_FALSE, 0, nullptr);
}

}  // namespace

CharacterMeshes::CharacterMeshes(std::span<const Character* const> characters)
    : characters_(characters.begin(), characters.end()) {
  for (const Character* character : characters) {
    const SkinnedMesh& mesh = character->mesh;
    CharacterMesh m;
    m.vertices = mesh.vertex_count();
    m.joints = character->skeleton.joint_count();
    m.index_count = static_cast<GLsizei>(mesh.indices.size());
    std::vector<uint32_t> both = mesh.indices;
    const std::vector<uint32_t> optimized = vertex_cache_order(mesh);
    both.insert(both.end(), optimized.begin(), optimized.end());
    m.indices = make_buffer(GL_ELEMENT_ARRAY_BUFFER, both.size() * sizeof(uint32_t), both.data(), GL_STATIC_DRAW);
    meshes_.push_back(m);
  }
}

MeshLevelDraw CharacterMesh::draw_of(size_t level, bool rest, IndexOrder order) const {
  if (level == 0 || levels.first_index.empty()) {
    const size_t first = order == IndexOrder::Optimized ? static_cast<size_t>(index_count) : 0;
    return {rest_vao, instanced_vao, indices, index_count, reinterpret_cast<const void*>(first * sizeof(uint32_t)), 0};
  }
  const size_t l = std::min(level, levels.first_index.size()) - 1;
  return {levels.rest_vao,
          levels.instanced_vao,
          levels.indices,
          levels.index_count[l],
          reinterpret_cast<const void*>(
              (order == IndexOrder::Optimized ? levels.first_optimized[l] : levels.first_index[l]) * sizeof(uint32_t)),
          rest ? static_cast<GLint>(levels.first_vertex[l]) : 0};
}

CharacterMeshes::~CharacterMeshes() {
  for (CharacterMesh& m : meshes_) {
    glDeleteVertexArrays(1, &m.levels.rest_vao);
    glDeleteVertexArrays(1, &m.levels.instanced_vao);
    glDeleteBuffers(1, &m.levels.indices);
    glDeleteBuffers(4, m.levels.rest_buffers);
    glDeleteVertexArrays(1, &m.rest_vao);
    glDeleteVertexArrays(1, &m.instanced_vao);
    glDeleteBuffers(1, &m.indices);
    glDeleteBuffers(4, m.rest_buffers);
  }
}

size_t CharacterMeshes::max_vertices() const {
  size_t most = 0;
  for (const CharacterMesh& m : meshes_) most = std::max(most, m.vertices);
  return most;
}

namespace {

// A rest mesh's four arrays in buffers, and a VAO reading them (attributes
// 0-3) with `indices`.
void upload_rest_arrays(const SkinnedMesh& mesh, GLuint indices, GLuint (&buffers)[4], std::span<GLuint* const> vaos) {
  const size_t vertices = mesh.vertex_count();
  buffers[0] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec3), mesh.positions.data(), GL_STATIC_DRAW);
  buffers[1] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec3), mesh.normals.data(), GL_STATIC_DRAW);
  buffers[2] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::u16vec4), mesh.joints.data(), GL_STATIC_DRAW);
  buffers[3] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec4), mesh.weights.data(), GL_STATIC_DRAW);
  for (GLuint* vao : vaos) {
    glGenVertexArrays(1, vao);
    glBindVertexArray(*vao);
    float_attribute(0, buffers[0], 3);
    float_attribute(1, buffers[1], 3);
    glBindBuffer(GL_ARRAY_BUFFER, buffers[2]);
    glEnableVertexAttribArray(2);
    glVertexAttribIPointer(2, 4, GL_UNSIGNED_SHORT, 0, nullptr);
    float_attribute(3, buffers[3], 4);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
  }
}

// The records of shaders/instances.glsl as a per-instance attribute of the
// bound VAO (copy, palette offset and the source words, one uvec4): llvmpipe
// fetches it once per instance, where reading it from a storage buffer costs
// a gather per vertex (docs/rendering.md).
void add_instance_attributes() {
  glEnableVertexAttribArray(kInstanceAttribute);
  glVertexAttribIFormat(kInstanceAttribute, 4, GL_UNSIGNED_INT, 0);
  glVertexAttribBinding(kInstanceAttribute, kInstanceStream);
  glVertexBindingDivisor(kInstanceStream, 1);
  // A fading baked copy's second slot (GpuFade), from the same stream at
  // twice the stride; enabled only around those draws (draw_instance_runs).
  glVertexAttribIFormat(kFadeAttribute, 4, GL_UNSIGNED_INT, sizeof(GpuInstance));
  glVertexAttribBinding(kFadeAttribute, kInstanceStream);
}

}  // namespace

void CharacterMeshes::upload_levels(size_t kind, std::span<const MeshLod> lods) {
  CharacterMesh::Levels& l = meshes_[kind].levels;
  if (l.rest_vao || lods.empty()) return;
  glBindVertexArray(0);  // binding the index buffer below must not change a VAO
  // Levels one after another: indices stay counted from each level's first
  // vertex, which the draw passes as its base vertex.
  SkinnedMesh all;
  for (const MeshLod& lod : lods) {
    l.first_index.push_back(all.indices.size());
    l.first_vertex.push_back(all.positions.size());
    l.index_count.push_back(static_cast<GLsizei>(lod.mesh.indices.size()));
    all.indices.insert(all.indices.end(), lod.mesh.indices.begin(), lod.mesh.indices.end());
    l.first_optimized.push_back(lod.cache_ordered ? l.first_index.back() : all.indices.size());
    if (!lod.cache_ordered) {
      const std::vector<uint32_t> optimized = vertex_cache_order(lod.mesh);
      all.indices.insert(all.indices.end(), optimized.begin(), optimized.end());
    }
    all.positions.insert(all.positions.end(), lod.mesh.positions.begin(), lod.mesh.positions.end());
    all.normals.insert(all.normals.end(), lod.mesh.normals.begin(), lod.mesh.normals.end());
    all.joints.insert(all.joints.end(), lod.mesh.joints.begin(), lod.mesh.joints.end());
    all.weights.insert(all.weights.end(), lod.mesh.weights.begin(), lod.mesh.weights.end());
  }
  l.indices =
      make_buffer(GL_ELEMENT_ARRAY_BUFFER, all.indices.size() * sizeof(uint32_t), all.indices.data(), GL_STATIC_DRAW);
  GLuint* vaos[] = {&l.rest_vao, &l.instanced_vao};
  upload_rest_arrays(all, l.indices, l.rest_buffers, vaos);
  add_instance_attributes();  // to the instanced VAO, bound last
  glBindVertexArray(0);
}

void CharacterMeshes::upload_rest_mesh(size_t kind) {
  CharacterMesh& m = meshes_[kind];
  if (m.rest_vao) return;
  // Two VAOs on the same buffers: one per copy, and one for instanced draws
  // that also reads each instance's record.
  GLuint* vaos[] = {&m.rest_vao, &m.instanced_vao};
  upload_rest_arrays(characters_[kind]->mesh, m.indices, m.rest_buffers, vaos);
  add_instance_attributes();
  glBindVertexArray(0);
}

}  // namespace crowdprof

#include "render/character_meshes.h"

#include <algorithm>

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
    m.indices = make_buffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices.size() * sizeof(uint32_t), mesh.indices.data(),
                            GL_STATIC_DRAW);
    meshes_.push_back(m);
  }
}

CharacterMeshes::~CharacterMeshes() {
  for (CharacterMesh& m : meshes_) {
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

void CharacterMeshes::upload_rest_mesh(size_t kind) {
  CharacterMesh& m = meshes_[kind];
  if (m.rest_vao) return;
  const SkinnedMesh& mesh = characters_[kind]->mesh;
  size_t vertices = m.vertices;
  m.rest_buffers[0] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec3), mesh.positions.data(), GL_STATIC_DRAW);
  m.rest_buffers[1] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec3), mesh.normals.data(), GL_STATIC_DRAW);
  m.rest_buffers[2] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::u16vec4), mesh.joints.data(), GL_STATIC_DRAW);
  m.rest_buffers[3] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec4), mesh.weights.data(), GL_STATIC_DRAW);
  // Two VAOs on the same buffers: one per copy, and one for instanced draws
  // that also reads each instance's record.
  for (GLuint* vao : {&m.rest_vao, &m.instanced_vao}) {
    glGenVertexArrays(1, vao);
    glBindVertexArray(*vao);
    float_attribute(0, m.rest_buffers[0], 3);
    float_attribute(1, m.rest_buffers[1], 3);
    glBindBuffer(GL_ARRAY_BUFFER, m.rest_buffers[2]);
    glEnableVertexAttribArray(2);
    glVertexAttribIPointer(2, 4, GL_UNSIGNED_SHORT, 0, nullptr);
    float_attribute(3, m.rest_buffers[3], 4);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.indices);
  }
  // The records of shaders/instances.glsl as per-instance attributes 4-8 (the
  // model's columns, then palette offset, colour and the source words): llvmpipe
  // fetches them once per instance, where reading them from the storage buffer
  // costs a gather per vertex (1.2x the CPU time, docs/rendering.md).
  for (GLuint column = 0; column < 4; ++column) {
    glEnableVertexAttribArray(4 + column);
    glVertexAttribFormat(4 + column, 4, GL_FLOAT, GL_FALSE, column * static_cast<GLuint>(sizeof(glm::vec4)));
    glVertexAttribBinding(4 + column, kInstanceStream);
  }
  glEnableVertexAttribArray(8);
  glVertexAttribIFormat(8, 4, GL_UNSIGNED_INT, static_cast<GLuint>(sizeof(glm::mat4)));
  glVertexAttribBinding(8, kInstanceStream);
  glVertexBindingDivisor(kInstanceStream, 1);
  glBindVertexArray(0);
}

}  // namespace crowdprof

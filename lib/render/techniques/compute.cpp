#include "render/techniques/compute.h"

#include <algorithm>
#include <cstring>
#include <span>

#include <glm/gtc/type_ptr.hpp>

#include "frame/frame_view.h"
#include "render/gl_errors.h"
#include "render/shader_sources.h"

namespace crowdprof {

namespace {

// The batch's vertex buffer holds at most this much (with one pass; with
// several, so that a pass sees more of the crowd before the next pass).
constexpr size_t kComputeBudgetBytes = size_t{64} << 20;
constexpr size_t kComputePassesBudgetBytes = size_t{1} << 30;
constexpr GLuint kComputeGroup = 64;  // skin.comp's local_size_x

}  // namespace

ComputeSkinning::ComputeSkinning() {
  std::string source(embedded_shader("shaders/skin.comp"));
  ShaderStage stage{GL_COMPUTE_SHADER, "shaders/skin.comp", source};
  skin_program_ = GlProgram(std::span(&stage, 1));
  vertex_count_ = skin_program_.uniform("vertex_count");
  joint_count_ = skin_program_.uniform("joint_count");
  draw_program_ = GlProgram(lit_stages("shaders/crowd.vert", ""));
  model_ = draw_program_.uniform("model");
  colour_ = draw_program_.uniform("base_colour");
  // Positions and normals interleaved, 32 bytes a vertex: attribute 1 is 16 bytes in.
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  for (GLuint attribute : {0u, 1u}) {
    glEnableVertexAttribArray(attribute);
    glVertexAttribFormat(attribute, 3, GL_FLOAT, GL_FALSE, attribute * 16);
    glVertexAttribBinding(attribute, 0);
  }
  glBindVertexArray(0);
}

ComputeSkinning::~ComputeSkinning() {
  glDeleteVertexArrays(1, &vao_);
  GLuint buffers[] = {bones_, skinned_};
  glDeleteBuffers(2, buffers);
  glDeleteBuffers(static_cast<GLsizei>(rest_storage_.size()), rest_storage_.data());
}

namespace {

// A mesh as skin.comp reads it: 64 bytes a vertex.
GLuint upload_rest_storage(const SkinnedMesh& mesh) {
  std::vector<glm::vec4> rest(4 * mesh.vertex_count());
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    rest[4 * v] = glm::vec4(mesh.positions[v], 1.0f);
    rest[4 * v + 1] = glm::vec4(mesh.normals[v], 0.0f);
    glm::uvec4 j(mesh.joints[v]);
    std::memcpy(&rest[4 * v + 2], &j, sizeof j);  // uvec4 in the shader: the bits, not the values
    rest[4 * v + 3] = mesh.weights[v];
  }
  return make_buffer(GL_SHADER_STORAGE_BUFFER, rest.size() * sizeof(glm::vec4), rest.data(), GL_STATIC_DRAW);
}

}  // namespace

void ComputeSkinning::prepare(const FrameView& view, const CharacterMeshes& meshes) {
  rest_storage_.resize(meshes.size() * kMeshLevels, 0);
  uint64_t bytes = 0;
  size_t vertices = 1, joints = 1;
  for (size_t k = 0; k < meshes.size(); ++k) {
    if (view.characters[k].site != SkinningSite::Compute) continue;
    const CharacterMesh& m = meshes[k];
    vertices = std::max(vertices, m.vertices);
    joints = std::max(joints, m.joints);
    // The full mesh, then each mesh level (mesh LOD; the same for every bench).
    std::span<const MeshLod> lods = view.characters[k].mesh_lods;
    for (size_t l = 0; l <= lods.size() && l < kMeshLevels; ++l) {
      const SkinnedMesh& mesh = l == 0 ? meshes.character(k).mesh : lods[l - 1].mesh;
      GLuint& storage = rest_storage_[k * kMeshLevels + l];
      if (!storage) storage = upload_rest_storage(mesh);
      bytes += mesh.vertex_count() * 4 * sizeof(glm::vec4);
    }
  }
  size_t copies = view.copies();
  size_t budget = view.mode.passes > 1 ? kComputePassesBudgetBytes : kComputeBudgetBytes;
  size_t batch = std::clamp<size_t>(budget / (vertices * 2 * sizeof(glm::vec4)), 1, std::max<size_t>(copies, 1));
  batch = std::min<size_t>(batch, 65535);  // the least GL_MAX_COMPUTE_WORK_GROUP_COUNT[1] GL promises
  if (batch != batch_ || vertices != vertices_ || joints != joints_) {
    glDeleteBuffers(1, &bones_);
    glDeleteBuffers(1, &skinned_);
    bones_ = make_buffer(GL_SHADER_STORAGE_BUFFER, batch * joints * 3 * sizeof(glm::vec4), nullptr, GL_STREAM_DRAW);
    skinned_ = make_buffer(GL_SHADER_STORAGE_BUFFER, batch * vertices * 2 * sizeof(glm::vec4), nullptr, GL_STREAM_COPY);
    batch_ = batch;
    vertices_ = vertices;
    joints_ = joints;
    rows_.assign(batch * joints * 3, glm::vec4(0));
  }
  copies_.reserve(copies);
  gpu_bytes_ = bytes + batch_ * (joints_ * 3 + vertices_ * 2) * sizeof(glm::vec4);
}

void ComputeSkinning::draw(const FrameView& view, const CharacterMeshes& meshes, std::span<const DrawPass> passes,
                           const BeginPass& begin_pass, Counters& counters) {
  for (size_t k = 0; k < meshes.size(); ++k)
    if (view.characters[k].site == SkinningSite::Compute) {
      // Without mesh LOD every copy is level 0: one scan of the crowd, not four.
      const size_t levels = view.mesh_level.empty() ? 1 : kMeshLevels;
      for (size_t level = 0; level < levels; ++level)
        draw_kind(view, meshes[k], k, level, passes, begin_pass, counters);
      counters.gpu_palette_bytes = gpu_bytes_;
    }
}

void ComputeSkinning::draw_kind(const FrameView& view, const CharacterMesh& mesh, size_t k, size_t level,
                                std::span<const DrawPass> passes, const BeginPass& begin_pass, Counters& counters) {
  copies_.clear();
  for (size_t i = 0; i < view.copies(); ++i)
    if (view.visible[i] && view.kind[i] == k && view.level_of(i) == level) copies_.push_back(i);
  if (copies_.empty()) return;
  const GLuint rest = rest_storage_.size() > k * kMeshLevels + level ? rest_storage_[k * kMeshLevels + level] : 0;
  if (!rest || mesh.joints > joints_ || mesh.vertices > vertices_)
    throw GlError("compute skinning asked of a renderer not prepared for it");
  const size_t level_vertices = view.vertices_of(copies_.front());
  const MeshLevelDraw drawn = mesh.draw_of(level, false, view.mode.index_order);
  auto vertices = static_cast<GLuint>(level_vertices);
  size_t copy_stride = level_vertices * 2 * sizeof(glm::vec4);
  const uint64_t palette_bytes = mesh.joints * 3 * sizeof(glm::vec4);
  for (size_t start = 0; start < copies_.size(); start += batch_) {
    size_t count = std::min(batch_, copies_.size() - start);
    for (size_t c = 0; c < count; ++c) {
      std::span<const SkinMatrix> palette = view.palette(copies_[start + c]);
      for (size_t j = 0; j < mesh.joints; ++j) put_rows(palette[j], &rows_[3 * (c * mesh.joints + j)]);
    }
    begin_pass(nullptr);
    // Fresh storage for both buffers (orphaning): the last batch's draws may still read them.
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, bones_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(batch_ * joints_ * 3 * sizeof(glm::vec4)), nullptr,
                 GL_STREAM_DRAW);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(count * mesh.joints * 3 * sizeof(glm::vec4)),
                    rows_.data());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, skinned_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(batch_ * vertices_ * 2 * sizeof(glm::vec4)), nullptr,
                 GL_STREAM_COPY);
    glUseProgram(skin_program_.id());
    glUniform1ui(vertex_count_, vertices);
    glUniform1ui(joint_count_, static_cast<GLuint>(mesh.joints));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, rest);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bones_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, skinned_);
    glDispatchCompute((vertices + kComputeGroup - 1) / kComputeGroup, static_cast<GLuint>(count), 1);
    // The draws below read what the pass wrote as vertex attributes.
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    count_palette_bytes(counters, count * palette_bytes);
    for (const DrawPass& pass : passes) {
      begin_pass(&pass);
      glUseProgram(draw_program_.id());
      set_frame_uniforms(draw_program_, pass);
      glBindVertexArray(vao_);
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, drawn.indices);
      for (size_t c = 0; c < count; ++c) {
        size_t i = copies_[start + c];
        glBindVertexBuffer(0, skinned_, static_cast<GLintptr>(c * copy_stride), 2 * sizeof(glm::vec4));
        glUniformMatrix4fv(model_, 1, GL_FALSE, glm::value_ptr(view.world[i]));
        glUniform3fv(colour_, 1, glm::value_ptr(copy_colour(i)));
        glDrawElements(GL_TRIANGLES, drawn.index_count, GL_UNSIGNED_INT, drawn.first_index);
        count_record_bytes(counters, kModelBytes);
        ++counters.draw_calls;
      }
    }
  }
}

}  // namespace crowdprof

#include "render/techniques/gpu_cull.h"

#include <algorithm>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "frame/frame_view.h"
#include "render/character_meshes.h"
#include "render/gl_errors.h"
#include "render/gpu_frame_buffers.h"
#include "render/shader_sources.h"
#include "render/techniques/technique.h"
#include "scene/camera.h"

namespace crowdprof {

namespace {

constexpr GLuint kCullGroup = 64;  // cull.comp's local_size_x

// cull.comp's CullCopy, std430: two vec4, then eight 4-byte fields.
struct CullCopy {
  glm::vec4 box_min, box_max;
  uint32_t kind, first_row, intervals;
  float phase, start, end, duration;
  uint32_t levels = 1;  // mesh levels of its character (1: no mesh LOD)
};
static_assert(sizeof(CullCopy) == GpuCull::kBytesPerCopy);

}  // namespace

GpuCull::GpuCull(const FrameView& view, const CharacterMeshes& meshes, std::span<const size_t> first_record,
                 std::span<const uint8_t> baked) {
  std::string source(embedded_shader("shaders/cull.comp"));
  ShaderStage stage{GL_COMPUTE_SHADER, "shaders/cull.comp", source};
  program_ = GlProgram(std::span(&stage, 1));
  planes_ = program_.uniform("planes");
  view_projection_ = program_.uniform("view_projection");
  thresholds_ = program_.uniform("lod_thresholds");
  per_kind_uniform_ = program_.uniform("commands_per_kind");
  seconds_ = program_.uniform("seconds");
  copy_count_ = program_.uniform("copy_count");
  check_record_stride();
  copy_count_value_ = view.copies();
  std::vector<CullCopy> copies(std::max<size_t>(copy_count_value_, 1));
  for (size_t i = 0; i < copy_count_value_; ++i) {
    const Aabb& box = view.world_boxes[i];
    const BakedClock& clock = view.baked_clocks[i];
    const auto levels = static_cast<uint32_t>(
        view.mode.mesh_lod ? std::min(view.character_of(i).mesh_lods.size() + 1, kMeshLevels) : 1);
    const auto first_row = static_cast<uint32_t>(3 * clock.first_sample * meshes[view.kind[i]].joints);
    copies[i] = {glm::vec4(box.min, 0.0f),
                 glm::vec4(box.max, 0.0f),
                 view.kind[i],
                 first_row,
                 clock.intervals,
                 clock.phase,
                 clock.start,
                 clock.end,
                 clock.duration,
                 levels};
  }
  copies_ = make_buffer(GL_SHADER_STORAGE_BUFFER, copies.size() * sizeof(CullCopy), copies.data(), GL_STATIC_DRAW);
  // One command per character, or with mesh LOD per character and level, even
  // for levels it lacks (never appended to, never drawn).
  per_kind_ = view.mode.mesh_lod ? kMeshLevels : 1;
  drawn_.assign(meshes.size() * per_kind_, 0);
  for (size_t g = 0; g < meshes.size() * per_kind_; ++g) {
    const size_t k = g / per_kind_, level = g % per_kind_;
    drawn_[g] = baked[k] && (level == 0 || (view.mode.mesh_lod && level <= view.characters[k].mesh_lods.size()));
    const MeshLevelDraw d = meshes[k].draw_of(level, true, view.mode.index_order);
    cleared_.push_back({static_cast<uint32_t>(d.index_count), 0,
                        static_cast<uint32_t>(reinterpret_cast<uintptr_t>(d.first_index) / sizeof(uint32_t)),
                        d.base_vertex, static_cast<uint32_t>(first_record[g])});
  }
  commands_ =
      make_buffer(GL_SHADER_STORAGE_BUFFER, cleared_.size() * sizeof(Command), cleared_.data(), GL_DYNAMIC_DRAW);
  gpu_bytes_ = copies.size() * sizeof(CullCopy) + cleared_.size() * sizeof(Command);
}

void GpuCull::check_record_stride() {
  // The stride of Instances' array, as this GL laid it out: the draws fetch
  // records sizeof(GpuInstance) apart.
  const GLuint variable = glGetProgramResourceIndex(program_.id(), GL_BUFFER_VARIABLE, "instances[0].copy");
  const GLenum property = GL_TOP_LEVEL_ARRAY_STRIDE;
  GLint stride = 0;
  if (variable != GL_INVALID_INDEX)
    glGetProgramResourceiv(program_.id(), GL_BUFFER_VARIABLE, variable, 1, &property, 1, nullptr, &stride);
  record_bytes_ = static_cast<uint64_t>(std::max(stride, 0));
  if (record_bytes_ != sizeof(GpuInstance))
    throw GlError("shaders/cull.comp writes records " + std::to_string(record_bytes_) +
                  " bytes apart; the draws read them " + std::to_string(sizeof(GpuInstance)) +
                  " bytes apart (GpuInstance)");
}

GpuCull::~GpuCull() {
  GLuint buffers[] = {copies_, commands_};
  glDeleteBuffers(2, buffers);
}

void GpuCull::run(const FrameView& view, GLuint instances, Counters& counters) {
  // The only bytes a frame sends: the commands with their counts at zero.
  const auto command_bytes = static_cast<GLsizeiptr>(cleared_.size() * sizeof(Command));
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, commands_);
  glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, command_bytes, cleared_.data());
  counters.bytes_uploaded += static_cast<uint64_t>(command_bytes);
  if (copy_count_value_ == 0) return;
  const Frustum frustum = frustum_of(view.view_projection);
  glUseProgram(program_.id());
  glUniform4fv(planes_, 6, glm::value_ptr(frustum.planes[0]));
  glUniformMatrix4fv(view_projection_, 1, GL_FALSE, glm::value_ptr(view.view_projection));
  const MeshLodThresholds& at = view.mode.mesh_lod_at;
  const float thresholds[3] = {at.level_1, at.level_2, at.level_3};
  glUniform1fv(thresholds_, 3, thresholds);
  glUniform1ui(per_kind_uniform_, static_cast<GLuint>(per_kind_));
  glUniform1d(seconds_, view.seconds);
  glUniform1ui(copy_count_, static_cast<GLuint>(copy_count_value_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, copies_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, instances);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, commands_);
  glDispatchCompute(static_cast<GLuint>((copy_count_value_ + kCullGroup - 1) / kCullGroup), 1, 1);
  // The draws read the records as per-instance attributes and their counts as
  // commands; the counts are read back, and the commands cleared next frame, by
  // buffer calls.
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

void GpuCull::draw(size_t k, const CharacterMesh& mesh, GLuint instances, Counters& counters) const {
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commands_);
  // The CPU does not know how many copies are on screen: one draw per character
  // and level, always (a level's own vertex array holds its indices).
  for (size_t level = 0; level < per_kind_; ++level) {
    const size_t g = k * per_kind_ + level;
    if (!drawn_[g]) continue;
    // The command's base_instance is where the level's records start.
    glBindVertexArray(mesh.draw_of(level, true, IndexOrder::File).instanced_vao);
    glBindVertexBuffer(kInstanceStream, instances, 0, sizeof(GpuInstance));
    glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(static_cast<uintptr_t>(g * sizeof(Command))));
    ++counters.draw_calls;
  }
}

void GpuCull::visible_counts(std::span<uint64_t> per_group) const {
  std::vector<Command> commands(cleared_.size());
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, commands_);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(commands.size() * sizeof(Command)),
                     commands.data());
  std::fill(per_group.begin(), per_group.end(), 0);
  for (size_t g = 0; g < commands.size(); ++g) {
    const size_t at = g / per_kind_ * kMeshLevels + g % per_kind_;
    if (at < per_group.size()) per_group[at] = drawn_[g] ? commands[g].instance_count : 0;
  }
}

}  // namespace crowdprof

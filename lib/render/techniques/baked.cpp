#include "render/techniques/baked.h"

#include <algorithm>

#include "frame/frame_view.h"
#include "render/gl_errors.h"

namespace crowdprof {

BakedSkinning::BakedSkinning() {
  program_ = GlProgram(lit_stages("shaders/baked.vert", "", "#define INSTANCED\n"));
  joint_count_ = program_.uniform("joint_count");
  first_instance_ = program_.uniform("first_instance");
}

BakedSkinning::~BakedSkinning() {
  GLuint buffers[] = {placements_, instances_};
  glDeleteBuffers(2, buffers);
  glDeleteBuffers(static_cast<GLsizei>(tables_.size()), tables_.data());
}

void BakedSkinning::prepare(const FrameView& view, CharacterMeshes& meshes) {
  tables_.resize(meshes.size(), 0);
  uint64_t bytes = 0;
  for (size_t k = 0; k < meshes.size(); ++k) {
    const BakedCharacter* baked = view.characters[k].site == SkinningSite::Baked ? view.characters[k].baked : nullptr;
    if (!baked) continue;
    meshes.upload_rest_mesh(k);
    std::vector<glm::vec4> rows(3 * baked->matrices.size());
    for (size_t m = 0; m < baked->matrices.size(); ++m) put_rows(baked->matrices[m], &rows[3 * m]);
    glDeleteBuffers(1, &tables_[k]);
    uint64_t table_bytes = rows.size() * sizeof(glm::vec4);
    tables_[k] = make_buffer(GL_SHADER_STORAGE_BUFFER, table_bytes, rows.data(), GL_STATIC_DRAW);
    bytes += table_bytes;
  }
  // Copies stand still: their placements go up once.
  size_t copies = view.copies();
  std::vector<glm::vec4> placements(5 * std::max<size_t>(copies, 1), glm::vec4(0));
  for (size_t i = 0; i < copies; ++i) {
    const glm::mat4& world = view.world[i];
    for (int c = 0; c < 4; ++c) placements[5 * i + static_cast<size_t>(c)] = world[c];
    placements[5 * i + 4] = glm::vec4(copy_colour(i), 1.0f);
  }
  glDeleteBuffers(1, &placements_);
  placements_ = make_buffer(GL_SHADER_STORAGE_BUFFER, placements.size() * sizeof(glm::vec4), placements.data(),
                            GL_STATIC_DRAW);
  if (instance_capacity_ < std::max<size_t>(copies, 1)) {
    instance_capacity_ = std::max<size_t>(copies, 1);
    glDeleteBuffers(1, &instances_);
    instances_ = make_buffer(GL_SHADER_STORAGE_BUFFER, instance_capacity_ * sizeof(InstanceRecord), nullptr,
                             GL_STREAM_DRAW);
  }
  records_.reserve(copies);
  gpu_bytes_ = bytes + placements.size() * sizeof(glm::vec4) + instance_capacity_ * sizeof(InstanceRecord);
  // A view at the address of one prepared before (a bench made where an
  // earlier one was) takes nothing of its cull pass.
  std::erase_if(culls_, [&](const auto& entry) { return entry.first == &view; });
  if (view.mode.frustum != FrustumTest::Gpu) return;
  // Each character's and level's records in a range as long as the
  // character's copies (any of them may take any level): the cull pass
  // appends to it, and its draw reads it.
  const size_t per_kind = view.mode.mesh_lod ? kMeshLevels : 1, groups = meshes.size() * per_kind;
  std::vector<size_t> first(groups + 1, 0);
  std::vector<uint8_t> baked(meshes.size(), 0);
  for (size_t i = 0; i < copies; ++i)
    for (size_t level = 0; level < per_kind; ++level) ++first[view.kind[i] * per_kind + level + 1];
  for (size_t g = 0; g < groups; ++g) first[g + 1] += first[g];
  for (size_t k = 0; k < meshes.size(); ++k) baked[k] = k < tables_.size() && tables_[k] != 0;
  if (instance_capacity_ < first[groups]) {
    instance_capacity_ = first[groups];
    glDeleteBuffers(1, &instances_);
    instances_ = make_buffer(GL_SHADER_STORAGE_BUFFER, instance_capacity_ * sizeof(InstanceRecord), nullptr,
                             GL_STREAM_DRAW);
    gpu_bytes_ = bytes + placements.size() * sizeof(glm::vec4) + instance_capacity_ * sizeof(InstanceRecord);
  }
  culls_.emplace_back(&view, std::make_unique<GpuCull>(view, meshes, first, baked));
  gpu_bytes_ += culls_.back().second->gpu_bytes();
}

GpuCull* BakedSkinning::cull_for(const FrameView& view) const {
  if (view.mode.frustum != FrustumTest::Gpu) return nullptr;
  for (const auto& [owner, cull] : culls_)
    if (owner == &view) return cull.get();
  return nullptr;
}

bool BakedSkinning::visible_counts(const FrameView& view, std::span<uint64_t> per_group) const {
  const GpuCull* cull = cull_for(view);
  if (!cull) return false;
  cull->visible_counts(per_group);
  return true;
}

void BakedSkinning::upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) {
  counters.gpu_palette_bytes = gpu_bytes_;
  if (GpuCull* cull = cull_for(view)) return cull->run(view, instances_, counters);
  if (view.mode.frustum == FrustumTest::Gpu) throw GlError("frustum gpu asked of a renderer not prepared for this bench");
  // This frame's instances, grouped by character and mesh level (one
  // instanced draw each), in copy order within a group: counted, then placed.
  const size_t groups = meshes.size() * kMeshLevels;
  for (size_t k = 0; k < meshes.size(); ++k)
    if (view.characters[k].site == SkinningSite::Baked && (k >= tables_.size() || !tables_[k]))
      throw GlError("baked skinning asked of a renderer not prepared for it");
  auto drawn = [&](size_t i) { return view.visible[i] && view.site_of(i) == SkinningSite::Baked; };
  auto group = [&](size_t i) { return view.kind[i] * kMeshLevels + view.level_of(i); };
  first_.assign(groups + 1, 0);
  for (size_t i = 0; i < view.copies(); ++i)
    if (drawn(i)) ++first_[group(i) + 1];
  for (size_t g = 0; g < groups; ++g) first_[g + 1] += first_[g];
  next_.assign(first_.begin(), first_.end() - 1);
  records_.resize(first_[groups]);
  for (size_t i = 0; i < view.copies(); ++i) {
    if (!drawn(i)) continue;
    const BakedInstance& b = view.baked[i];
    records_[next_[group(i)]++] = {static_cast<uint32_t>(i), b.first_sample, b.intervals, b.position};
  }
  if (records_.empty()) return;
  auto bytes = static_cast<GLsizeiptr>(records_.size() * sizeof(InstanceRecord));
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, instances_);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(instance_capacity_ * sizeof(InstanceRecord)), nullptr,
               GL_STREAM_DRAW);  // orphaned, as the CPU path's buffers
  glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes, records_.data());
  counters.bytes_uploaded += static_cast<uint64_t>(bytes);
}

void BakedSkinning::draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass,
                         Counters& counters) {
  const GpuCull* gpu_cull = cull_for(view);
  if (records_.empty() && !gpu_cull) return;
  glUseProgram(program_.id());
  set_frame_uniforms(program_, pass);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, placements_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, instances_);
  for (size_t k = 0; k < meshes.size(); ++k) {
    if (gpu_cull) {
      if (k >= tables_.size() || !tables_[k]) continue;
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, tables_[k]);
      glUniform1ui(joint_count_, static_cast<GLuint>(meshes[k].joints));
      gpu_cull->draw(k, meshes[k], first_instance_, counters);
      continue;
    }
    for (size_t l = 0; l < kMeshLevels; ++l) {
      const size_t g = k * kMeshLevels + l;
      auto count = static_cast<GLsizei>(first_[g + 1] - first_[g]);
      if (count == 0) continue;
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, tables_[k]);
      glUniform1ui(joint_count_, static_cast<GLuint>(meshes[k].joints));
      glUniform1ui(first_instance_, static_cast<GLuint>(first_[g]));
      const MeshLevelDraw level = meshes[k].draw_of(l, true);
      glBindVertexArray(level.vao);
      glDrawElementsInstancedBaseVertex(GL_TRIANGLES, level.index_count, GL_UNSIGNED_INT, level.first_index, count,
                                        level.base_vertex);
      ++counters.draw_calls;
    }
  }
  if (gpu_cull) glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);  // no later draw reads commands by accident
}

}  // namespace crowdprof

#include "render/techniques/instanced.h"

#include <glm/gtc/type_ptr.hpp>

#include "frame/frame_view.h"
#include "render/techniques/buffer_palette.h"

namespace crowdprof {

Instanced::Instanced(CharacterMeshes& meshes, const GlFeatures& gl) : gl_(gl) {
  program_ = GlProgram(buffer_palette_stages(true, gl));
  for (size_t k = 0; k < meshes.size(); ++k) meshes.upload_rest_mesh(k);
}

uint64_t Instanced::bytes_per_copy(const CharacterMesh& mesh) {
  return mesh.joints * 3 * sizeof(glm::vec4) + sizeof(GpuInstance);
}

void Instanced::upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) {
  counters.bytes_uploaded += placements_.update(view, gl_);  // nothing once the crowd is placed
  const SentBytes sent = send_palettes(view, meshes, buffers_, on_screen_, gl_, true);
  count_palette_bytes(counters, sent.palettes);
  count_record_bytes(counters, sent.records);
  counters.gpu_palette_bytes = buffers_.gpu_bytes() + placements_.gpu_bytes();
}

void Instanced::draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) {
  glUseProgram(program_.id());
  set_frame_uniforms(program_, pass);
  set_copy_colours(program_);
  draw_instance_runs(
      buffers_, placements_, meshes, view.mode.index_order, [](size_t) {}, counters);
}

void draw_instance_runs(const GpuFrameBuffers& buffers, const GpuPlacements& placements, const CharacterMeshes& meshes,
                        IndexOrder order, const std::function<void(size_t)>& bind_character, Counters& counters,
                        RecordRuns runs) {
  const GLsizei stride = static_cast<GLsizei>(runs.slots * sizeof(GpuInstance));
  size_t bound = SIZE_MAX;
  for (size_t group = 0; group < meshes.size() * kMeshLevels; ++group) {
    const InstanceRun run = buffers.run(runs.first_group + group);
    if (run.count == 0) continue;
    const size_t k = group / kMeshLevels;
    if (k != bound) bind_character(bound = k);
    // A character's copies at one mesh level (draw_group): level 0 without mesh LOD.
    const MeshLevelDraw level = meshes[k].draw_of(group % kMeshLevels, true, order);
    glBindVertexArray(level.instanced_vao);
    if (runs.slots > 1) glEnableVertexAttribArray(kFadeAttribute);
    // One instanced draw per page the group's palettes and placements take
    // (one, below the storage-block limit).
    for (uint32_t from = run.first; from < run.first + run.count;) {
      const InstanceRun part = buffers.page_run(runs.first_group + group, from);
      buffers.bind_page(buffers.page_of(from));
      placements.bind_page(buffers.placement_page_of(from));
      glBindVertexBuffer(kInstanceStream, buffers.instance_buffer(),
                         static_cast<GLintptr>(part.first) * static_cast<GLintptr>(sizeof(GpuInstance)), stride);
      glDrawElementsInstancedBaseVertex(GL_TRIANGLES, level.index_count, GL_UNSIGNED_INT, level.first_index,
                                        static_cast<GLsizei>(part.count / runs.slots), level.base_vertex);
      from += part.count;
      ++counters.draw_calls;
    }
    // The VAO's other draws read one slot a record.
    if (runs.slots > 1) glDisableVertexAttribArray(kFadeAttribute);
  }
}

void set_copy_colours(const GlProgram& program) {
  glUniform3fv(program.uniform("colours"), static_cast<GLsizei>(kCopyColours.size()), glm::value_ptr(kCopyColours[0]));
}

std::string copy_colours_define() {
  return "#define COLOURS " + std::to_string(kCopyColours.size()) + "\n";
}

}  // namespace crowdprof

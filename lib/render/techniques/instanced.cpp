#include "render/techniques/instanced.h"

#include <glm/gtc/type_ptr.hpp>

#include "frame/frame_view.h"
#include "render/techniques/buffer_palette.h"

namespace crowdprof {

Instanced::Instanced(CharacterMeshes& meshes, const GlFeatures& gl) : gl_(gl) {
  program_ = GlProgram(buffer_palette_stages(true));
  for (size_t k = 0; k < meshes.size(); ++k) meshes.upload_rest_mesh(k);
}

uint64_t Instanced::bytes_per_copy(const CharacterMesh& mesh) {
  return mesh.joints * 3 * sizeof(glm::vec4) + sizeof(GpuInstance);
}

void Instanced::upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) {
  counters.bytes_uploaded += send_palettes(view, meshes, buffers_, on_screen_, gl_, true);
  counters.gpu_palette_bytes = buffers_.gpu_bytes();
}

void Instanced::draw(const FrameView&, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) {
  glUseProgram(program_.id());
  set_frame_uniforms(program_, pass);
  glUniform3fv(program_.uniform("colours"), static_cast<GLsizei>(kCopyColours.size()),
               glm::value_ptr(kCopyColours[0]));
  for (size_t group = 0; group < meshes.size() * kMeshLevels; ++group) {
    const InstanceRun run = buffers_.run(group);
    if (run.count == 0) continue;
    // A character's copies at one mesh level (draw_group): level 0 without mesh LOD.
    const MeshLevelDraw level = meshes[group / kMeshLevels].draw_of(group % kMeshLevels, true);
    glBindVertexArray(level.instanced_vao);
    // One instanced draw per page the group's palettes take (one, below the storage-block limit).
    for (uint32_t from = run.first; from < run.first + run.count;) {
      const InstanceRun part = buffers_.page_run(group, from);
      buffers_.bind_page(buffers_.page_of(from));
      glBindVertexBuffer(kInstanceStream, buffers_.instance_buffer(),
                         static_cast<GLintptr>(part.first) * static_cast<GLintptr>(sizeof(GpuInstance)),
                         sizeof(GpuInstance));
      glDrawElementsInstancedBaseVertex(GL_TRIANGLES, level.index_count, GL_UNSIGNED_INT, level.first_index,
                                        static_cast<GLsizei>(part.count), level.base_vertex);
      from += part.count;
      ++counters.draw_calls;
    }
  }
}

}  // namespace crowdprof

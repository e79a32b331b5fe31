#include "render/techniques/uniform_palette.h"

#include <algorithm>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "frame/frame_view.h"
#include "render/gl_errors.h"

namespace crowdprof {

UniformPalette::UniformPalette(CharacterMeshes& meshes, size_t bone_limit) : bone_limit_(bone_limit) {
  program_ = GlProgram(lit_stages("shaders/hwskin.vert", "#define MAX_BONES " + std::to_string(bone_limit) + "\n"));
  model_ = program_.uniform("model");
  colour_ = program_.uniform("base_colour");
  bones_ = program_.uniform("bones");
  size_t most_joints = 0;
  for (size_t k = 0; k < meshes.size(); ++k) {
    if (meshes[k].joints > bone_limit) continue;
    meshes.upload_rest_mesh(k);
    most_joints = std::max(most_joints, meshes[k].joints);
  }
  rows_.resize(3 * most_joints);
}

uint64_t UniformPalette::bytes_per_copy(const CharacterMesh& mesh) {
  return mesh.joints * 3 * sizeof(glm::vec4) + kModelBytes;
}

void UniformPalette::upload(const FrameView&, const CharacterMeshes&, Counters& counters) {
  counters.gpu_palette_bytes = 3 * sizeof(glm::vec4) * bone_limit_;  // the uniform array
}

// Each draw sends its copy's palette: every pass sends it again.
void UniformPalette::draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass,
                          Counters& counters) {
  glUseProgram(program_.id());
  set_frame_uniforms(program_, pass);
  for (size_t i = 0; i < view.copies(); ++i) {
    size_t k = view.kind[i];
    if (!view.visible[i] || view.characters[k].site != SkinningSite::Gpu) continue;
    const CharacterMesh& mesh = meshes[k];
    if (!mesh.rest_vao || mesh.joints > bone_limit_)
      throw GlError("GPU skinning asked of a renderer whose character is over its bone limit");
    const MeshLevelDraw level = mesh.draw_of(view.level_of(i), true, view.mode.index_order);
    glBindVertexArray(level.vao);
    std::span<const SkinMatrix> palette = view.palette(i);
    for (size_t j = 0; j < mesh.joints; ++j) put_rows(palette[j], &rows_[3 * j]);
    if (mesh.joints > 0) glUniform4fv(bones_, static_cast<GLsizei>(3 * mesh.joints), glm::value_ptr(rows_[0]));
    glUniformMatrix4fv(model_, 1, GL_FALSE, glm::value_ptr(view.world[i]));
    glUniform3fv(colour_, 1, glm::value_ptr(copy_colour(i)));
    glDrawElementsBaseVertex(GL_TRIANGLES, level.index_count, GL_UNSIGNED_INT, level.first_index, level.base_vertex);
    count_palette_bytes(counters, bytes_per_copy(mesh) - kModelBytes);
    count_record_bytes(counters, kModelBytes);
    ++counters.draw_calls;
  }
}

}  // namespace crowdprof

#include "render/techniques/buffer_palette.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "frame/frame_view.h"
#include "render/shader_sources.h"
#include "render/techniques/instanced.h"

namespace crowdprof {

namespace {

// Skinned in the vertex shader from a palette the CPU computed (hwskin, buffer,
// instanced), not by compute or from baked samples.
bool palette_copy(const FrameView& view, size_t copy) {
  return view.site_of(copy) == SkinningSite::Gpu;
}

}  // namespace

std::vector<ShaderStage> buffer_palette_stages(bool instanced, const GlFeatures& gl) {
  std::string defines = instanced ? "#define INSTANCED\n" + copy_colours_define() +
                                        GpuPlacements::shader_source(PlacementBlock::Uniform, gl)
                                  : "";
  defines += std::string(embedded_shader("shaders/instances.glsl"));
  return lit_stages("shaders/buffer_skin.vert", defines, instanced ? "#define INSTANCED\n" : "");
}

SentBytes send_palettes(const FrameView& view, const CharacterMeshes& meshes, GpuFrameBuffers& buffers,
                        std::vector<uint32_t>& on_screen, const GlFeatures& gl, bool instanced) {
  size_t copies = 0, rows = 0, largest = 0;
  on_screen.assign(meshes.size() * kMeshLevels, 0);
  for (size_t i = 0; i < view.copies(); ++i) {
    if (!palette_copy(view, i)) continue;
    ++copies;
    rows += 3 * meshes[view.kind[i]].joints;
    largest = std::max<size_t>(largest, 3 * meshes[view.kind[i]].joints);
    on_screen[draw_group(view, i)] += view.visible[i];
  }
  buffers.reserve(copies, rows, largest, instanced, gl);
  buffers.begin(on_screen);
  for (size_t i = 0; i < view.copies(); ++i) {
    if (!view.visible[i] || !palette_copy(view, i)) continue;
    size_t k = view.kind[i];
    std::span<const SkinMatrix> palette = view.palette(i);
    std::span<glm::vec4> out = buffers.add(draw_group(view, i), static_cast<uint32_t>(i), 3 * meshes[k].joints);
    for (size_t j = 0; j < meshes[k].joints; ++j) put_rows(palette[j], &out[3 * j]);
  }
  return buffers.upload(instanced);
}

BufferPalette::BufferPalette(CharacterMeshes& meshes, const GlFeatures& gl) : gl_(gl) {
  program_ = GlProgram(buffer_palette_stages(false, gl));
  model_ = program_.uniform("model");
  colour_ = program_.uniform("base_colour");
  base_ = program_.uniform("palette_base");
  for (size_t k = 0; k < meshes.size(); ++k) meshes.upload_rest_mesh(k);  // no bone limit
  next_.resize(meshes.size() * kMeshLevels);
}

void BufferPalette::upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) {
  count_palette_bytes(counters, send_palettes(view, meshes, buffers_, on_screen_, gl_, false).palettes);
  counters.gpu_palette_bytes = buffers_.palette_gpu_bytes();
}

void BufferPalette::draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass,
                         Counters& counters) {
  glUseProgram(program_.id());
  set_frame_uniforms(program_, pass);
  for (size_t g = 0; g < next_.size(); ++g) next_[g] = buffers_.run(g).first;
  uint32_t bound = UINT32_MAX;  // another technique may have bound its own buffer since upload()
  for (size_t i = 0; i < view.copies(); ++i) {
    if (!view.visible[i] || !palette_copy(view, i)) continue;
    size_t k = view.kind[i];
    const MeshLevelDraw level = meshes[k].draw_of(view.level_of(i), true, view.mode.index_order);
    glBindVertexArray(level.vao);
    const uint32_t record = next_[draw_group(view, i)]++;
    if (buffers_.page_of(record) != bound) buffers_.bind_page(bound = buffers_.page_of(record));
    glUniform1ui(base_, buffers_.palette_base(record));
    glUniformMatrix4fv(model_, 1, GL_FALSE, glm::value_ptr(view.world[i]));
    glUniform3fv(colour_, 1, glm::value_ptr(copy_colour(i)));
    glDrawElementsBaseVertex(GL_TRIANGLES, level.index_count, GL_UNSIGNED_INT, level.first_index, level.base_vertex);
    count_record_bytes(counters, kModelBytes);  // the palette went up in upload()
    ++counters.draw_calls;
  }
}

}  // namespace crowdprof

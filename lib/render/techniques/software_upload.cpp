#include "render/techniques/software_upload.h"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

#include "frame/frame_view.h"
#include "skinning/packed_vertex.h"

namespace crowdprof {

namespace {

// The stream buffers hold at most this much: enough for every copy of the
// thesis scene (160 x 119 KB), bounded for crowds of thousands.
constexpr size_t kStreamBudgetBytes = size_t{64} << 20;

}  // namespace

SoftwareUpload::SoftwareUpload(const CharacterMeshes& meshes, size_t copies) {
  float_program_ = GlProgram(lit_stages("shaders/crowd.vert", ""));
  float_model_ = float_program_.uniform("model");
  float_colour_ = float_program_.uniform("base_colour");
  size_t copy_bytes = std::max<size_t>(2 * meshes.max_vertices() * sizeof(glm::vec3), 1);
  stream_.resize(std::clamp<size_t>(kStreamBudgetBytes / copy_bytes, 1, std::max<size_t>(copies, 1)));
  for (GLuint& buffer : stream_) buffer = make_buffer(GL_ARRAY_BUFFER, copy_bytes, nullptr, GL_STREAM_DRAW);
  // Attributes 0 and 1 read bindings 0 and 1, which each draw points at its buffer.
  glGenVertexArrays(1, &float_vao_);
  glBindVertexArray(float_vao_);
  for (GLuint attribute : {0u, 1u}) {
    glEnableVertexAttribArray(attribute);
    glVertexAttribFormat(attribute, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexAttribBinding(attribute, attribute);
  }
  // Packed vertices: positions as 3 normalised 16-bit codes, normals as one
  // signed normalised 10:10:10:2 word (its 2-bit w unused by the shader).
  packed_program_ = GlProgram(lit_stages("shaders/crowd.vert", "#define PACKED_POSITIONS 1\n"));
  packed_model_ = packed_program_.uniform("model");
  packed_colour_ = packed_program_.uniform("base_colour");
  packed_min_ = packed_program_.uniform("position_min");
  packed_extent_ = packed_program_.uniform("position_extent");
  glGenVertexArrays(1, &packed_vao_);
  glBindVertexArray(packed_vao_);
  glEnableVertexAttribArray(0);
  glVertexAttribFormat(0, 3, GL_UNSIGNED_SHORT, GL_TRUE, 0);
  glVertexAttribBinding(0, 0);
  glEnableVertexAttribArray(1);
  glVertexAttribFormat(1, 4, GL_INT_2_10_10_10_REV, GL_TRUE, 0);
  glVertexAttribBinding(1, 1);
  glBindVertexArray(0);
}

SoftwareUpload::~SoftwareUpload() {
  glDeleteVertexArrays(1, &float_vao_);
  glDeleteVertexArrays(1, &packed_vao_);
  glDeleteBuffers(static_cast<GLsizei>(stream_.size()), stream_.data());
}

uint64_t SoftwareUpload::bytes_per_copy(const CharacterMesh& mesh) {
  return mesh.vertices * 2 * sizeof(glm::vec3) + kModelBytes;
}

GLuint SoftwareUpload::stream_buffer(size_t drawn, bool own) {
  // One pass cycles through the budget's buffers; several passes keep each
  // copy's vertices until the last pass, so each copy drawn needs its own.
  if (!own) return stream_[drawn % stream_.size()];
  while (stream_.size() <= drawn) stream_.push_back(make_buffer(GL_ARRAY_BUFFER, 1, nullptr, GL_STREAM_DRAW));
  return stream_[drawn];
}

void SoftwareUpload::use_program(const FrameView& view, const DrawPass& pass) const {
  const GlProgram& program = view.packed() ? packed_program_ : float_program_;
  glUseProgram(program.id());
  set_frame_uniforms(program, pass);
  glBindVertexArray(view.packed() ? packed_vao_ : float_vao_);
}

void SoftwareUpload::upload(const FrameView& view, const CharacterMeshes&, Counters& counters) {
  placed_.clear();
  if (view.mode.passes <= 1) return;
  size_t drawn = 0;
  shown_storage_ = SIZE_MAX;
  for (size_t i = 0; i < view.copies(); ++i) {
    if (!view.visible[i] || skins_on_gpu(view.site_of(i))) continue;
    placed_.push_back(view.packed() ? place_packed(view, i, drawn++, counters)
                                    : place_float(view, i, drawn++, counters));
  }
}

void SoftwareUpload::draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass,
                          Counters& counters) {
  use_program(view, pass);
  if (view.mode.passes > 1) {
    for (const Placed& p : placed_) draw_placed(view, meshes[view.kind[p.copy]], p, true, counters);
    return;
  }
  size_t drawn = 0;
  shown_storage_ = SIZE_MAX;
  for (size_t i = 0; i < view.copies(); ++i) {
    if (!view.visible[i] || skins_on_gpu(view.site_of(i))) continue;
    const CharacterMesh& mesh = meshes[view.kind[i]];
    Placed p = view.packed() ? place_packed(view, i, drawn++, counters) : place_float(view, i, drawn++, counters);
    draw_placed(view, mesh, p, p.fresh, counters);
  }
}

SoftwareUpload::Placed SoftwareUpload::place_float(const FrameView& view, size_t i, size_t drawn, Counters& counters) {
  auto half = static_cast<GLsizeiptr>(view.vertices_of(i) * sizeof(glm::vec3));
  // Animation sharing: a copy in the state the last draw uploaded draws that
  // mesh again with its own transform (the thesis scene: one upload a frame).
  if (view.mode.share_poses && view.storage_of(i) == shown_storage_) return {i, shown_buffer_, half, false};
  GLuint buffer = stream_buffer(drawn, view.mode.passes > 1);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  // Fresh storage (orphaning) before writing: writing into storage that a
  // draw may still read makes the driver wait for it. llvmpipe waits even
  // for the last frame's finished draws, so without it every upload waits.
  glBufferData(GL_ARRAY_BUFFER, 2 * half, nullptr, GL_STREAM_DRAW);
  glBufferSubData(GL_ARRAY_BUFFER, 0, half, view.skinned_positions(i).data());
  glBufferSubData(GL_ARRAY_BUFFER, half, half, view.skinned_normals(i).data());
  counters.bytes_uploaded += 2 * static_cast<uint64_t>(half);  // the model goes with the draw
  shown_storage_ = view.storage_of(i);
  shown_buffer_ = buffer;
  return {i, buffer, half, true};
}

SoftwareUpload::Placed SoftwareUpload::place_packed(const FrameView& view, size_t i, size_t drawn, Counters& counters) {
  auto positions = static_cast<GLsizeiptr>(view.vertices_of(i) * kPackedPositionBytes);
  auto normals = static_cast<GLsizeiptr>(view.vertices_of(i) * kPackedNormalBytes);
  GLuint buffer = stream_buffer(drawn, view.mode.passes > 1);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  // Normals start on a 4-byte boundary: the words are read whole.
  GLintptr normals_at = (positions + 3) / 4 * 4;
  glBufferData(GL_ARRAY_BUFFER, normals_at + normals, nullptr, GL_STREAM_DRAW);  // orphaned, as above
  glBufferSubData(GL_ARRAY_BUFFER, 0, positions, view.packed_positions_of(i).data());
  glBufferSubData(GL_ARRAY_BUFFER, normals_at, normals, view.packed_normals_of(i).data());
  counters.bytes_uploaded += view.vertices_of(i) * kPackedVertexBytes;
  return {i, buffer, normals_at, true};
}

void SoftwareUpload::draw_placed(const FrameView& view, const CharacterMesh& mesh, const Placed& p, bool send_model,
                                 Counters& counters) {
  size_t i = p.copy;
  const MeshLevelDraw level = mesh.draw_of(view.level_of(i), false, view.mode.index_order);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, level.indices);  // part of the VAO: the copy's character's (level's)
  if (view.packed()) {
    glBindVertexBuffer(0, p.buffer, 0, static_cast<GLsizei>(kPackedPositionBytes));
    glBindVertexBuffer(1, p.buffer, p.normals_at, static_cast<GLsizei>(kPackedNormalBytes));
    const PositionQuantisation& q = view.character_of(i).quantisation;
    glUniform3fv(packed_min_, 1, glm::value_ptr(q.min));
    glUniform3fv(packed_extent_, 1, glm::value_ptr(q.extent));
    glUniformMatrix4fv(packed_model_, 1, GL_FALSE, glm::value_ptr(view.world[i]));
    glUniform3fv(packed_colour_, 1, glm::value_ptr(copy_colour(i)));
  } else {
    glBindVertexBuffer(0, p.buffer, 0, sizeof(glm::vec3));
    glBindVertexBuffer(1, p.buffer, p.normals_at, sizeof(glm::vec3));
    glUniformMatrix4fv(float_model_, 1, GL_FALSE, glm::value_ptr(view.world[i]));
    glUniform3fv(float_colour_, 1, glm::value_ptr(copy_colour(i)));
  }
  glDrawElements(GL_TRIANGLES, level.index_count, GL_UNSIGNED_INT, level.first_index);
  // A copy drawing the mesh the last one uploaded (sharing) was counted as
  // sending nothing; the thesis scene's counters keep that.
  if (send_model) counters.bytes_uploaded += kModelBytes;
  ++counters.draw_calls;
}

}  // namespace crowdprof

// Copies skinned on the CPU (modes master, culled, threaded; copies over the
// GPU's bone limit): each copy's skinned vertices go up every frame into a
// buffer of their own, as the BGE gave each mesh its own, then one draw. With
// --vertex-format packed the vertices are 16-bit position codes and
// 10:10:10:2 normals that the vertex shader decodes.
#pragma once

#include <cstdint>
#include <vector>

#include "render/character_meshes.h"
#include "render/techniques/technique.h"

namespace crowdprof {

class SoftwareUpload final : public Technique {
 public:
  // Stream buffers for up to `copies` copies of the largest character, within
  // a budget (buffers serve several copies beyond it).
  SoftwareUpload(const CharacterMeshes& meshes, size_t copies);
  ~SoftwareUpload() override;

  // With one pass, nothing: each copy's vertices go up just before its draw,
  // as the BGE did. With several, every copy on screen that the CPU skinned
  // goes up once, into a buffer of its own, for every pass to draw.
  void upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) override;
  // The copies on screen that the CPU skinned.
  void draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) override;

  // Bytes one float copy of `mesh` costs to send: positions, normals, model.
  static uint64_t bytes_per_copy(const CharacterMesh& mesh);

 private:
  // A copy's vertices in a stream buffer: where each attribute starts.
  struct Placed {
    size_t copy = 0;
    GLuint buffer = 0;
    GLintptr normals_at = 0;
    bool fresh = true;  // uploaded for this copy (false: sharing the last one's)
  };
  Placed place_float(const FrameView& view, size_t copy, size_t drawn, Counters& counters);
  Placed place_packed(const FrameView& view, size_t copy, size_t drawn, Counters& counters);
  void draw_placed(const FrameView& view, const CharacterMesh& mesh, const Placed& placed, bool send_model,
                   Counters& counters);
  void use_program(const FrameView& view, const DrawPass& pass) const;
  GLuint stream_buffer(size_t drawn, bool own);

  GlProgram float_program_, packed_program_;
  GLint float_model_ = -1, float_colour_ = -1;
  GLint packed_model_ = -1, packed_colour_ = -1, packed_min_ = -1, packed_extent_ = -1;
  GLuint float_vao_ = 0, packed_vao_ = 0;
  // A buffer per drawn copy (positions, then normals), orphaned and refilled
  // every frame.
  std::vector<GLuint> stream_;
  // With animation sharing, the storage (FrameView::storage_of) whose mesh the last
  // draw uploaded, and the buffer holding it: copies in the same state after it
  // draw that buffer with their own transform, uploading nothing.
  size_t shown_storage_ = SIZE_MAX;
  GLuint shown_buffer_ = 0;
  std::vector<Placed> placed_;  // several passes: this frame's copies, uploaded
};

}  // namespace crowdprof

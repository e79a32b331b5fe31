// Each copy's placement on the GPU (issue 52 item 3): its model matrix, in a
// buffer indexed by copy. A placed copy does not move, so the instanced and
// baked records that name it (gpu_frame_buffers.h) carry only what changes
// each frame; the placements are sent again only where they differ from what
// was sent (shaders/placements.glsl reads them). The copy's colour needs no
// room: it follows from the copy's index (copy_colour), as from its index in
// its page.
//
// The vertex shader reads them as a uniform block, in pages of one block
// (1,362 copies in 64 KiB): a record names its copy from its page's first, and
// a draw binds its page (bind_page). On llvmpipe a storage block's element is
// gathered per vertex, CPU time every frame, where a uniform block's costs
// about nothing (docs/modes.md). frustum gpu's indirect draws
// cannot change pages, so past one page its shader reads them as one storage
// block (bind_storage).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/gl.h"
#include "render/gl_features.h"

namespace crowdprof {

struct FrameView;

// One copy's element of Placements (shaders/placements.glsl): the model
// matrix's upper 3x4 as rows (a placement is affine, its fourth row 0 0 0 1),
// 48 bytes, not 64, in std140 and std430 alike.
struct GpuPlacement {
  glm::vec4 rows[3] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
};
static_assert(sizeof(GpuPlacement) == 48, "three vec4 of shaders/placements.glsl");

// The placements' binding point, uniform or storage, as shaders/placements.glsl names it.
inline constexpr GLuint kPlacementBinding = 1;

// How a vertex shader reads the placements.
enum class PlacementBlock { Uniform, Storage };

class GpuPlacements {
 public:
  GpuPlacements() = default;
  ~GpuPlacements();
  GpuPlacements(const GpuPlacements&) = delete;
  GpuPlacements& operator=(const GpuPlacements&) = delete;

  // Copies a uniform page holds: as many as a uniform block of `gl` takes,
  // each page starting where a bound range may start, in whole cycles of
  // kCopyColours.
  static size_t copies_per_page(const GlFeatures& gl);
  // shaders/placements.glsl with what it needs defined, for a vertex shader
  // that reads the placements as `block` (after copy_colours_define()).
  static std::string shader_source(PlacementBlock block, const GlFeatures& gl);

  // Sends the placements of `view`'s copies that differ from those last sent
  // (all of them the first time, or when the crowd's size changed); returns
  // the bytes sent. Throws GlError for a placement that is not affine.
  uint64_t update(const FrameView& view, const GlFeatures& gl);
  // Binds uniform page `page` (copies from page x copies_per_page on) at
  // kPlacementBinding, for the draws that follow.
  void bind_page(uint32_t page) const;
  // Binds them all as a storage block at kPlacementBinding.
  void bind_storage() const;
  // Bytes of GPU storage they hold.
  uint64_t gpu_bytes() const { return sent_.size() * sizeof(GpuPlacement); }

 private:
  std::vector<GpuPlacement> sent_;  // what the buffer holds
  std::vector<GpuPlacement> now_;   // scratch: this frame's
  GLuint buffer_ = 0;
  size_t page_copies_ = 1;
};

}  // namespace crowdprof

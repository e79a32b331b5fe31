// The buffer palettes drawn with one instanced draw per character (mode
// instanced, --draw instanced): each instance reads its copy and palette
// offset from a 16-byte record (render/gpu_frame_buffers.h) fetched as
// per-instance vertex attributes, and its copy's model matrix and colour from
// the placements, sent once (render/gpu_placements.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/character_meshes.h"
#include "render/gl_features.h"
#include "render/gpu_frame_buffers.h"
#include "render/gpu_placements.h"
#include "render/techniques/technique.h"

namespace crowdprof {

// Which of a frame's runs draw_instance_runs draws: the draw groups from
// `first_group` on, one per character and mesh level, whose records take
// `slots` 16-byte slots each (2: fading baked copies', each GpuInstance
// followed by its GpuFade, read at kFadeAttribute).
struct RecordRuns {
  size_t first_group = 0;
  uint32_t slots = 1;
};

// The instanced path that instanced and baked share: one instanced draw per
// draw group (character and mesh level: draw_group) and palette page of the
// runs begin() reserved in `buffers`, each instance reading its record as
// per-instance attributes through the level's instanced VAO and its copy's
// placement from `placements`; triangles in `order`. The program is
// bound; `bind_character(k)` binds what character k's draws read besides
// (baked: its table and joint count), before its first draw.
void draw_instance_runs(const GpuFrameBuffers& buffers, const GpuPlacements& placements, const CharacterMeshes& meshes,
                        IndexOrder order, const std::function<void(size_t)>& bind_character, Counters& counters,
                        RecordRuns runs = {});

// kCopyColours into `program`'s uniform `colours`, which a record's colour
// indexes; its shader is compiled with copy_colours_define() (COLOURS, their
// number).
void set_copy_colours(const GlProgram& program);
std::string copy_colours_define();

class Instanced final : public Technique {
 public:
  // Uploads every character's rest mesh. Needs vertex-stage storage buffers.
  Instanced(CharacterMeshes& meshes, const GlFeatures& gl);

  void upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) override;
  void draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) override;

  // Bytes one copy of `mesh` costs to send a frame: its palette's rows and its
  // record (its placement went once).
  static uint64_t bytes_per_copy(const CharacterMesh& mesh);

 private:
  GlFeatures gl_;
  GlProgram program_;
  GpuFrameBuffers buffers_;
  GpuPlacements placements_;
  std::vector<uint32_t> on_screen_;  // scratch: per character, copies on screen
};

}  // namespace crowdprof

// What a frame hands its renderer: spans of the crowd's data as the frame
// left it, read-only. The renderer draws from these and calls nothing back;
// the bench owns the arrays (they never move while it lives) and sets the
// per-frame fields before each draw.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "animation/bake.h"
#include "animation/skin_matrix.h"
#include "asset/mesh_lod.h"
#include "base/modes.h"
#include "scene/bounds.h"
#include "skinning/packed_vertex.h"

namespace crowdprof {

// What a character's copies share, as a renderer needs it.
struct CharacterView {
  SkinningSite site = SkinningSite::CpuInAnimations;  // the mode's, or the CPU over the GPU's bone limit
  size_t joints = 0, vertices = 0;
  const BakedCharacter* baked = nullptr;  // mode baked only
  PositionQuantisation quantisation;      // packed vertices: the box positions are packed in
  std::span<const MeshLod> mesh_lods;     // mesh LOD: levels 1.. (prepared_character.h)
};

// Where a copy drawn with a baked table reads it this frame: its action's
// first sample, the action's interval count and the position among them.
struct BakedInstance {
  uint32_t first_sample = 0, intervals = 1;
  float position = 0.0f;
};

// With transitions, the action a baked copy fades from (issue 53): where it
// reads that action's samples (its time advancing with crossfade sampled,
// held at the change with frozen) and that action's weight, 0 when the copy is
// not fading (then the rest is not sent).
struct BakedFade {
  uint32_t first_sample = 0, intervals = 1;
  float position = 0.0f;
  float weight = 0.0f;  // of the action left: 1 - the fade's
  bool fading() const { return weight > 0.0f; }
};

// What a copy's baked record is made from when the GPU makes it (frustum gpu):
// fixed at load, the time coming from FrameView::seconds. Its action's sample
// 0 in the table and interval count, its phase, and its action's start, end
// and duration (0: a character without actions, always at sample 0).
struct BakedClock {
  uint32_t first_sample = 0, intervals = 1;
  float phase = 0.0f, start = 0.0f, end = 0.0f, duration = 0.0f;
};

struct FrameView {
  uint64_t frame = 0;  // the bench's frame number (0 for the first)
  double seconds = 0;  // the simulated clock this frame: frame / fps
  ModeSwitches mode;
  glm::mat4 view_projection{1.0f};
  // mode.passes > 2: each shadow cascade's camera (scene/shadow_cascades.h).
  std::span<const glm::mat4> shadow_view_projections;
  std::span<const CharacterView> characters;  // per character
  // Per copy.
  std::span<const uint16_t> kind;  // index into characters
  std::span<const glm::mat4> world;
  std::span<const uint8_t> visible;          // inside the frustum this frame
  std::span<const uint32_t> shown;           // the pose storage it draws (sharing), empty: its own
  std::span<const BakedInstance> baked;      // mode baked: this frame's, for copies on screen
  std::span<const BakedFade> baked_fades;    // mode baked with transitions: as baked; empty without
  std::span<const Aabb> world_boxes;         // what frustum gpu tests (the CPU's test reads the same)
  std::span<const BakedClock> baked_clocks;  // mode baked with frustum gpu: fixed at load
  std::span<const uint8_t> mesh_level;       // mesh LOD: the level each copy draws; empty: all level 0
  // Per pose storage (one per copy): where its palette and vertices start.
  std::span<const size_t> joint_offset, vertex_offset;
  std::span<const SkinMatrix> palettes;           // every storage's skinning matrices
  std::span<const glm::vec3> positions, normals;  // float vertices skinned on the CPU
  std::span<const uint16_t> packed_positions;     // packed: 3 codes a vertex
  std::span<const uint32_t> packed_normals;

  size_t copies() const { return kind.size(); }
  const CharacterView& character_of(size_t copy) const { return characters[kind[copy]]; }
  SkinningSite site_of(size_t copy) const { return character_of(copy).site; }
  // Every character skinned on the GPU (vertex shader, compute or baked).
  bool gpu_skinned() const;
  bool packed() const { return mode.vertex_format == VertexFormat::Packed; }
  size_t storage_of(size_t copy) const { return shown.empty() ? copy : shown[copy]; }
  size_t level_of(size_t copy) const { return mesh_level.empty() ? 0 : mesh_level[copy]; }
  // Vertices of the mesh the copy draws: its level's.
  size_t vertices_of(size_t copy) const {
    const size_t level = level_of(copy);
    return level == 0 ? character_of(copy).vertices : character_of(copy).mesh_lods[level - 1].mesh.vertex_count();
  }
  std::span<const SkinMatrix> palette(size_t copy) const {
    return palettes.subspan(joint_offset[storage_of(copy)], character_of(copy).joints);
  }
  std::span<const glm::vec3> skinned_positions(size_t copy) const { return float_span(positions, copy); }
  std::span<const glm::vec3> skinned_normals(size_t copy) const { return float_span(normals, copy); }
  // Copies the GPU skins keep no vertices on the CPU: empty for them.
  std::span<const uint16_t> packed_positions_of(size_t copy) const {
    if (!packed() || skins_on_gpu(site_of(copy))) return {};
    return packed_positions.subspan(3 * vertex_offset[storage_of(copy)], 3 * vertices_of(copy));
  }
  std::span<const uint32_t> packed_normals_of(size_t copy) const {
    if (!packed() || skins_on_gpu(site_of(copy))) return {};
    return packed_normals.subspan(vertex_offset[storage_of(copy)], vertices_of(copy));
  }

 private:
  std::span<const glm::vec3> float_span(std::span<const glm::vec3> all, size_t copy) const {
    if (packed() || skins_on_gpu(site_of(copy))) return {};
    return all.subspan(vertex_offset[storage_of(copy)], vertices_of(copy));
  }
};

inline bool FrameView::gpu_skinned() const {
  for (const CharacterView& c : characters)
    if (!skins_on_gpu(c.site)) return false;
  return true;
}

}  // namespace crowdprof

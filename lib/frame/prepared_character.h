// What a bench prepares once per character and never changes while it runs:
// sizes, where the character's copies are skinned, its actions' bindings, its
// mesh prepared for skinning, and (mode baked) its baked actions. Shared by
// every copy of the character (ozz-animation's runtime data).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "animation/bake.h"
#include "animation/binding.h"
#include "animation/layering.h"
#include "animation/local_pose.h"
#include "asset/character.h"
#include "asset/mesh_lod.h"
#include "frame/frame_view.h"
#include "base/modes.h"
#include "scene/bounds.h"
#include "scene/crowd.h"
#include "skinning/packed_vertex.h"
#include "skinning/skinning_plan.h"
#include "result/result.h"

namespace crowdprof {

struct PreparedCharacter {
  size_t joints = 0, vertices = 0, max_channels = 0;
  // The mode's site, except that a character over the GPU's bone limit is
  // skinned on the CPU, in Animations (thesis §4.4).
  SkinningSite site = SkinningSite::CpuInAnimations;
  // Has actions and is posed on the CPU (baked copies never are: the GPU reads
  // their samples); a character without actions stands in its rest pose.
  bool posed_on_cpu = false;
  std::vector<ActionBindings> bindings;  // per action
  LocalPose rest_pose;                   // what a blend falls back to (animation/blending.h)
  CharacterLayers layers;                // --anim-layer, resolved; empty without it
  SkinningPlan skinning_plan;            // the mesh prepared for skinning
  BakedCharacter baked;                  // mode baked only
  PositionQuantisation quantisation;     // packed vertices: the character's animated box
  // Mesh LOD only: the simplified levels (level L is mesh_lods[L - 1]; level 0
  // is the character's own mesh) and each one's plan for skinning.
  std::vector<MeshLod> mesh_lods;
  std::vector<SkinningPlan> lod_plans;

  // Levels a copy can draw, the full mesh counted.
  size_t levels() const { return 1 + mesh_lods.size(); }
  const SkinningPlan& plan_of(size_t level) const { return level == 0 ? skinning_plan : lod_plans[level - 1]; }
  size_t vertices_of(size_t level) const { return level == 0 ? vertices : mesh_lods[level - 1].mesh.vertex_count(); }
};

// Prepares each character for `mode`; `boxes` are the characters' animated
// bounds (Crowd::character_boxes), `max_gpu_joints` the renderer's bone limit
// for the mode (0 without a renderer), `layers` each character's layers (a
// scene group's own, else mode.anim_layers: kind_layers). Allocates; a
// load-time step.
std::vector<PreparedCharacter> prepare_characters(std::span<const Character* const> characters,
                                                  std::span<const Aabb> boxes, const ModeSwitches& mode,
                                                  size_t max_gpu_joints,
                                                  std::span<const std::vector<AnimLayer>> layers);

// Each character's layers: those of the group that plays it when the group
// states its own (a scene file's "layers"), else the mode's.
std::vector<std::vector<AnimLayer>> kind_layers(size_t characters, std::span<const CrowdGroup> groups,
                                                const ModeSwitches& mode);

// Whether any character has a layer (a blend per copy, and cursors per layer).
bool any_layers(std::span<const PreparedCharacter> prepared);

// Mode baked, at load: bakes every character's actions at `rate_hz` into
// prepared[k].baked (a character without actions: its rest palette twice, one
// interval, so the shader's table has one shape) and measures the deviation.
// Returns what baking cost and how far it strays (result/result.h BakeRecord:
// the worst character's deviation; bake_ms over every action of every character).
BakeRecord bake_characters(std::span<const Character* const> characters, float rate_hz,
                           std::span<PreparedCharacter> prepared);

// A character's skinning matrices in its rest pose. Allocates.
std::vector<SkinMatrix> rest_palette(const Character& character);

// The renderer's view of each prepared character.
std::vector<CharacterView> character_views(std::span<const PreparedCharacter> prepared);

}  // namespace crowdprof

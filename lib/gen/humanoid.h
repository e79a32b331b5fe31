// A deterministic procedural humanoid: the project's stand-in for the thesis's
// character (a 69-bone armature and a 4,951-vertex mesh, dancing), which is not
// public. Y-up, metres, about 1.8 m tall, facing +Z, bound in a T-pose.
#pragma once

#include <cstdint>

#include "asset/character.h"

namespace crowdprof {

// Which looping actions the humanoid gets: the thesis's stand-ins (dance,
// walk, wave: scenes/humanoid.glb), or a game crowd's locomotion (idle, walk,
// run: what transitions fade between, issue 53). Walk is the same in both.
enum class HumanoidActions : uint8_t { Default, Locomotion };

struct HumanoidOptions {
  int bones = 69;       // exact joint count, kHumanoidMinBones..kHumanoidMaxBones
  int vertices = 4951;  // exact vertex count, kHumanoidMinVertices..kHumanoidMaxVertices
  uint32_t seed = 1;    // varies proportions and motion slightly
  // 0 to 3: coarser tessellations of the same body on the same rig, with a
  // half, a quarter and a tenth of the vertices (at least kHumanoidMinVertices,
  // each fewer than the one before), as Character::file_lods: what a glTF
  // file's own levels (MSFT_lod) look like when gltf_writer writes them.
  int lod_levels = 0;
  HumanoidActions actions = HumanoidActions::Default;
};

inline constexpr int kHumanoidMinBones = 20;  // hips, spine, neck, head, limbs without fingers
inline constexpr int kHumanoidMaxBones = 1024;
inline constexpr int kHumanoidMinVertices = 500;  // the coarsest body with every part
// The body has about two triangles per vertex, so six indices: the most whose
// index accessor the loader still accepts (kMaxAccessorElements), with room.
inline constexpr int kHumanoidMaxVertices = 2'500'000;

// Builds the character: exactly `bones` joints in parent-before-child order and
// exactly `vertices` vertices in one primitive, every vertex on a triangle, with
// up to 4 influences sorted largest first and summing to 1. Three looping
// actions, "dance", "walk" and "wave" (or "idle", "walk" and "run" with
// HumanoidActions::Locomotion), key a rotation for every joint (and the
// root's translation) at 30 fps with LINEAR interpolation; each moves every joint.
//
// 69 bones: hips, spine_01-04, neck_01-02, head, jaw and per side a clavicle,
// two upper-arm and two forearm segments, a hand, four metacarpals, 5 fingers of
// 3 phalanges, two thigh segments, calf, foot and ball. Fewer bones drop the
// metacarpals, phalanges, fingers, segments and jaw; more subdivide the spine,
// limbs, fingers and neck, so the body keeps its shape at any count.
//
// The same options give the same character, bit for bit, from any x86-64
// build: it is computed in double precision and every value is rounded to a
// 2^-24 grid before it becomes a float, so FMA contraction and libm rounding
// do not show. Throws UsageError for options out of range.
Character generate_humanoid(const HumanoidOptions& options = {});

}  // namespace crowdprof

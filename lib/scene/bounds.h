// Axis-aligned boxes, and the box a character stays inside whatever it plays.
#pragma once

#include <glm/glm.hpp>

#include "asset/character.h"

namespace crowdprof {

struct Aabb {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  glm::vec3 center() const { return (min + max) * 0.5f; }
  glm::vec3 size() const { return max - min; }
};

// The box of `aabb` after `transform` (the box around its eight moved corners).
Aabb transform_aabb(const Aabb& aabb, const glm::mat4& transform);

// A conservative box in the character's own space around every pose it takes:
// each action is sampled at its keys and between them (`samples_per_action`
// evenly spaced times as well), skinned, and the boxes joined, then padded by
// `padding` of the diagonal. The BGE culled with the mesh's bounds; crowdprof's
// copies animate in place, so one box per character serves every frame and a
// copy's visibility never depends on the pose it was culled in.
Aabb animated_bounds(const Character& character, int samples_per_action = 32, float padding = 0.05f);

// As animated_bounds, around the poses of one action only (the rest pose not
// included; a character without actions: the rest pose). The tighter box an
// engine gets by bounding each clip (the culling audit's "own action").
Aabb action_bounds(const Character& character, size_t action, int samples_per_action = 32, float padding = 0.05f);

// The mesh's own box as stored (its bind pose), unpadded: what an engine culls
// with when it takes a skinned mesh's bounds from the file.
Aabb bind_pose_bounds(const Character& character);

}  // namespace crowdprof

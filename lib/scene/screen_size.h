// How big a copy looks: the share of the screen's height its box spans, for
// update-rate LOD and the animation budget (issue 13), and the mesh level that
// size picks (mesh LOD, issue 29).
#pragma once

#include <glm/glm.hpp>

#include "scene/bounds.h"

namespace crowdprof {

// Half the extent in normalised device y of the box's eight projected corners
// (1: the box spans the screen's height), not clipped to the screen: a copy
// half off-screen is as big as it would be on it. A corner at or behind the
// eye makes the box fill the view: 1.
float screen_height_fraction(const glm::mat4& view_projection, const Aabb& box);

// The mesh level (0: full; 1 to 3: coarser) a copy spanning `fraction` of the
// screen's height draws, given the level it drew (`current`): below
// thresholds[0] level 1, below [1] level 2, below [2] level 3, at most
// `levels` - 1 (the levels the character has, the full mesh counted).
// Hysteresis: it moves to a finer level only when `fraction` is at least
// (1 + hysteresis) times that level's threshold, so a copy at a threshold
// keeps its level. A NaN fraction keeps `current`.
uint8_t mesh_level_for(float fraction, uint8_t current, const float (&thresholds)[3], float hysteresis, size_t levels);

}  // namespace crowdprof

// How big a copy looks: the share of the screen's height its box spans, for
// update-rate LOD and the animation budget (issue 13).
#pragma once

#include <glm/glm.hpp>

#include "scene/bounds.h"

namespace crowdprof {

// Half the extent in normalised device y of the box's eight projected corners
// (1: the box spans the screen's height), not clipped to the screen: a copy
// half off-screen is as big as it would be on it. A corner at or behind the
// eye makes the box fill the view: 1.
float screen_height_fraction(const glm::mat4& view_projection, const Aabb& box);

}  // namespace crowdprof

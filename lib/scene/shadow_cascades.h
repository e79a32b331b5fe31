// Cascaded shadow maps' cameras (issue 30's passes): the part of the camera's
// view that holds the crowd, cut into slices by depth, each slice seen by an
// orthographic camera looking along the light. A cascade's draw is the work
// a real frame spends on shadows; crowdprof does not sample the maps, so the
// colour image stays the one without them.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "scene/bounds.h"
#include "scene/camera.h"

namespace crowdprof {

// Towards the light: above, in front, to the right (what every lit shader uses).
inline const glm::vec3 kLightDirection = glm::normalize(glm::vec3(0.4f, 0.8f, 0.6f));

// The view depths (distances along the camera's axis) where cascades start
// and end: count + 1 of them, from where the crowd's box starts in front of
// the camera to where it ends, split half logarithmically, half evenly (the
// "practical" split of Zhang et al.), so near cascades are smaller.
std::vector<float> cascade_splits(const Camera& camera, const Aabb& crowd_box, size_t count);

// One view-projection per cascade: an orthographic box along `light` (towards
// the light) around the slice of the camera's frustum between two splits,
// deepened towards the light to the whole crowd so that every caster in front
// of the slice is drawn.
std::vector<glm::mat4> shadow_cascades(const Camera& camera, const Aabb& crowd_box, glm::vec3 light, size_t count);

}  // namespace crowdprof

// One copy's joint transforms relative to their parents (translation, rotation,
// scale per joint, structure of arrays), as the sampling job writes them and the
// local-to-model job reads them.
#pragma once

#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "asset/character.h"

namespace crowdprof {

struct LocalPose {
  std::vector<glm::vec3> translations;
  std::vector<glm::quat> rotations;  // unit length
  std::vector<glm::vec3> scales;

  size_t joint_count() const { return translations.size(); }
};

// Sizes `pose` for `skeleton` (allocating when it grows) and sets every joint to
// its rest transform. Not a job: call it once per copy, and again before sampling
// an action that leaves some joints unanimated.
void reset_to_rest(const Skeleton& skeleton, LocalPose* pose);

}  // namespace crowdprof

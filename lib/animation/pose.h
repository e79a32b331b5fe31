// From a copy's local pose to the matrices skinning needs: model-space joint
// transforms in parent order, then skinning matrices (model x inverse bind).
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "animation/local_pose.h"
#include "animation/skin_matrix.h"
#include "asset/character.h"

namespace crowdprof {

// model[j] = model[parent] * parent_offsets[j] * TRS(j); for a root,
// parent_offsets[j] * TRS(j). The offset multiply is skipped where the offset is
// exactly the identity, as it is for almost every joint, found by a 64-byte
// compare that costs less than the multiply it saves.
struct LocalToModelJob {
  const Skeleton* skeleton = nullptr;
  const LocalPose* input = nullptr;
  std::span<glm::mat4> output;  // one per joint

  // Pointers set, the skeleton's arrays and the pose sized alike, parents before
  // children, `output` one per joint.
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// output[j] = model[j] * inverse_binds[j]: the matrix that takes a bind-pose
// vertex to where joint j puts it now.
struct SkinningMatricesJob {
  const Skeleton* skeleton = nullptr;
  std::span<const glm::mat4> model;  // one per joint, from LocalToModelJob
  std::span<SkinMatrix> output;      // one per joint

  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

}  // namespace crowdprof

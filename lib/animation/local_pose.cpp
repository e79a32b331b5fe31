#include "animation/local_pose.h"

namespace crowdprof {

void reset_to_rest(const Skeleton& skeleton, LocalPose* pose) {
  // assign() reuses the vectors' storage when it is large enough.
  pose->translations.assign(skeleton.rest_translations.begin(), skeleton.rest_translations.end());
  pose->rotations.assign(skeleton.rest_rotations.begin(), skeleton.rest_rotations.end());
  pose->scales.assign(skeleton.rest_scales.begin(), skeleton.rest_scales.end());
}

}  // namespace crowdprof

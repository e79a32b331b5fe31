#include "animation/exact_palette.h"

#include "animation/pose.h"
#include "animation/run_job.h"

namespace crowdprof {

std::span<const SkinMatrix> ExactPalette::at(const Skeleton& skeleton, const Action* action,
                                             std::span<const int32_t> targets, float time) {
  model.resize(skeleton.joint_count());
  palette.resize(skeleton.joint_count());
  reset_to_rest(skeleton, &pose);
  if (action) {
    reset_cursor(*action, &cursor);
    run_job(SamplingJob{action, time, targets, &cursor, &pose}, "SamplingJob");
  }
  run_job(LocalToModelJob{&skeleton, &pose, model}, "LocalToModelJob");
  run_job(SkinningMatricesJob{&skeleton, model, palette}, "SkinningMatricesJob");
  return palette;
}

}  // namespace crowdprof

#include "animation/exact_palette.h"

#include "animation/blending.h"
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

std::span<const SkinMatrix> ExactPalette::fading(const Skeleton& skeleton, const LocalPose& rest, const Action& from,
                                                 std::span<const int32_t> from_targets, float from_time,
                                                 const Action& action, std::span<const int32_t> targets, float time,
                                                 float weight) {
  model.resize(skeleton.joint_count());
  palette.resize(skeleton.joint_count());
  reset_to_rest(skeleton, &from_pose);
  reset_cursor(from, &cursor);
  run_job(SamplingJob{&from, from_time, from_targets, &cursor, &from_pose}, "SamplingJob");
  reset_to_rest(skeleton, &pose);
  reset_cursor(action, &cursor);
  run_job(SamplingJob{&action, time, targets, &cursor, &pose}, "SamplingJob");
  const BlendLayer layers[] = {{&from_pose, 1.0f - weight}, {&pose, weight}};
  run_job(BlendingJob{layers, &rest, 0.1f, &pose}, "BlendingJob");
  run_job(LocalToModelJob{&skeleton, &pose, model}, "LocalToModelJob");
  run_job(SkinningMatricesJob{&skeleton, model, palette}, "SkinningMatricesJob");
  return palette;
}

}  // namespace crowdprof

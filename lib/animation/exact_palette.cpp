#include "animation/exact_palette.h"

#include "animation/blending.h"
#include "animation/pose.h"
#include "animation/run_job.h"

namespace crowdprof {

const LocalPose* ExactPalette::lay(const Skeleton& skeleton, std::span<const BlendLayer> own, const Action& action,
                                   float time, const ExactLayers& layers) {
  if (!layers.layers || layers.layers->empty()) return own.front().pose;
  const size_t count = layers.layers->layers.size();
  layer_poses.resize(count);
  deltas.resize(count);
  for (size_t l = 0; l < count; ++l) {
    const size_t a = layers.layers->layers[l].action;
    const Action& layer_action = layers.actions[a];
    reset_to_rest(skeleton, &layer_poses[l]);
    reset_cursor(layer_action, &cursor);
    run_job(SamplingJob{&layer_action, layer_time(action, time, layer_action), layers.bindings[a].targets, &cursor,
                        &layer_poses[l]},
            "SamplingJob");
  }
  layered = *layers.rest;
  run_job(LayeringJob{layers.layers, own, layer_poses, deltas, layers.rest, &layered}, "LayeringJob");
  return &layered;
}

std::span<const SkinMatrix> ExactPalette::at(const Skeleton& skeleton, const Action* action,
                                             std::span<const int32_t> targets, float time, const ExactLayers& layers) {
  model.resize(skeleton.joint_count());
  palette.resize(skeleton.joint_count());
  reset_to_rest(skeleton, &pose);
  const LocalPose* shown = &pose;
  if (action) {
    reset_cursor(*action, &cursor);
    run_job(SamplingJob{action, time, targets, &cursor, &pose}, "SamplingJob");
    const BlendLayer alone[] = {{&pose, 1.0f}};
    shown = lay(skeleton, alone, *action, time, layers);
  }
  run_job(LocalToModelJob{&skeleton, shown, model}, "LocalToModelJob");
  run_job(SkinningMatricesJob{&skeleton, model, palette}, "SkinningMatricesJob");
  return palette;
}

std::span<const SkinMatrix> ExactPalette::fading(const Skeleton& skeleton, const LocalPose& rest, const Action& from,
                                                 std::span<const int32_t> from_targets, float from_time,
                                                 const Action& action, std::span<const int32_t> targets, float time,
                                                 float weight, const ExactLayers& layers) {
  model.resize(skeleton.joint_count());
  palette.resize(skeleton.joint_count());
  reset_to_rest(skeleton, &from_pose);
  reset_cursor(from, &cursor);
  run_job(SamplingJob{&from, from_time, from_targets, &cursor, &from_pose}, "SamplingJob");
  reset_to_rest(skeleton, &pose);
  reset_cursor(action, &cursor);
  run_job(SamplingJob{&action, time, targets, &cursor, &pose}, "SamplingJob");
  const BlendLayer own[] = {{&from_pose, 1.0f - weight}, {&pose, weight}};
  const LocalPose* shown = &pose;
  if (layers.layers && !layers.layers->empty()) {
    shown = lay(skeleton, own, action, time, layers);
  } else {
    run_job(BlendingJob{own, &rest, 0.1f, &pose}, "BlendingJob");
  }
  run_job(LocalToModelJob{&skeleton, shown, model}, "LocalToModelJob");
  run_job(SkinningMatricesJob{&skeleton, model, palette}, "SkinningMatricesJob");
  return palette;
}

}  // namespace crowdprof

#include "skinning/bake_deviation.h"
#include "animation/run_job.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "animation/pose.h"
#include "asset/standing.h"
#include "skinning/skinning.h"

namespace crowdprof {

bool BakeDeviationJob::Validate() const {
  if (!skeleton || !action || !plan || !cursor || !pose || !max_deviation || intervals == 0) return false;
  size_t joints = skeleton->joint_count(), vertices = plan->vertex_count;
  return targets.size() == action->channels.size() && baked.size() == (intervals + 1) * joints &&
         model.size() == joints && exact.size() == joints && interpolated.size() == joints &&
         pose->joint_count() == joints && cursor->keys.size() == action->channels.size() &&
         exact_positions.size() == vertices && baked_positions.size() == vertices && normals.size() == vertices;
}

bool BakeDeviationJob::Run() const {
  if (!Validate()) return false;
  size_t joints = skeleton->joint_count(), vertices = plan->vertex_count;
  float worst = *max_deviation;
  for (size_t i = 0; i < intervals; ++i)
    for (int p = 1; p <= kDeviationProbes; ++p) {
      float position = static_cast<float>(i) + static_cast<float>(p) / (kDeviationProbes + 1);
      float time = action->start + action->duration() * position / static_cast<float>(intervals);
      reset_to_rest(*skeleton, pose);
      run_job(SamplingJob{action, time, targets, cursor, pose}, "SamplingJob");
      run_job(LocalToModelJob{skeleton, pose, model}, "LocalToModelJob");
      run_job(SkinningMatricesJob{skeleton, model, exact}, "SkinningMatricesJob");
      run_job(BakedPaletteJob{baked, joints, position, interpolated}, "BakedPaletteJob");
      run_job(SkinningJob{exact, plan, 0, vertices, exact_positions, normals}, "SkinningJob");
      run_job(SkinningJob{interpolated, plan, 0, vertices, baked_positions, normals}, "SkinningJob");
      for (size_t v = 0; v < vertices; ++v)
        worst = std::max(worst, glm::distance(exact_positions[v], baked_positions[v]));
    }
  *max_deviation = worst;
  return true;
}

BakeDeviation measure_bake_deviation(const Character& character, std::span<const std::span<const int32_t>> targets,
                                     const BakedCharacter& baked, const SkinningPlan& plan) {
  BakeDeviation result;
  result.height = standing_of(character).height;
  const Skeleton& skeleton = character.skeleton;
  size_t joints = skeleton.joint_count(), vertices = plan.vertex_count;
  LocalPose pose;
  reset_to_rest(skeleton, &pose);
  SamplingCursor cursor;
  std::vector<glm::mat4> model(joints);
  std::vector<SkinMatrix> exact(joints), interpolated(joints);
  std::vector<glm::vec3> exact_positions(vertices), baked_positions(vertices), normals(vertices);
  for (size_t a = 0; a < character.actions.size() && a < targets.size(); ++a) {
    const Action& action = character.actions[a];
    reset_cursor(action, &cursor);
    run_job(
        BakeDeviationJob{&skeleton, &action, targets[a], baked.action(a), baked.intervals[a], &plan, &cursor, &pose,
                         model, exact, interpolated, exact_positions, baked_positions, normals, &result.model_units},
        "BakeDeviationJob");
  }
  return result;
}

}  // namespace crowdprof

#include "scene/bounds.h"
#include "animation/run_job.h"

#include <algorithm>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "animation/binding.h"
#include "animation/local_pose.h"
#include "animation/pose.h"
#include "animation/sampling.h"
#include "skinning/skinning.h"

namespace crowdprof {

Aabb transform_aabb(const Aabb& aabb, const glm::mat4& transform) {
  Aabb out{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec3 p((corner & 1) ? aabb.max.x : aabb.min.x, (corner & 2) ? aabb.max.y : aabb.min.y,
                (corner & 4) ? aabb.max.z : aabb.min.z);
    glm::vec3 q = glm::vec3(transform * glm::vec4(p, 1.0f));
    out.min = glm::min(out.min, q);
    out.max = glm::max(out.max, q);
  }
  return out;
}

namespace {

// Skins the whole mesh in the pose `local` and grows `box` around it.
void grow_by_pose(const Character& c, const SkinningPlan& plan, const LocalPose& local, std::vector<glm::mat4>& model,
                  std::vector<SkinMatrix>& palette, std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals,
                  Aabb& box) {
  run_job(LocalToModelJob{&c.skeleton, &local, model}, "LocalToModelJob");
  run_job(SkinningMatricesJob{&c.skeleton, model, palette}, "SkinningMatricesJob");
  run_job(SkinningJob{palette, &plan, 0, c.mesh.vertex_count(), positions, normals}, "SkinningJob");
  for (const glm::vec3& p : positions) {
    box.min = glm::min(box.min, p);
    box.max = glm::max(box.max, p);
  }
}

}  // namespace

namespace {

// The box around the poses of the actions `actions` (and the rest pose when
// `with_rest`), padded as animated_bounds says.
Aabb bounds_of_poses(const Character& c, std::span<const size_t> actions, bool with_rest, int samples_per_action,
                     float padding) {
  Aabb box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
  if (c.mesh.vertex_count() == 0) return Aabb{};
  SkinningPlan plan;
  if (std::string why = build_skinning_plan(c.mesh, c.skeleton.joint_count(), &plan); !why.empty())
    throw std::runtime_error("skinning plan: " + why);  // the loader checked the same: a bug if reached
  size_t joints = c.skeleton.joint_count();
  std::vector<glm::mat4> model(joints);
  std::vector<SkinMatrix> palette(joints);
  std::vector<glm::vec3> positions(c.mesh.vertex_count()), normals(c.mesh.vertex_count());
  LocalPose local;
  reset_to_rest(c.skeleton, &local);
  if (with_rest || actions.empty()) grow_by_pose(c, plan, local, model, palette, positions, normals, box);
  for (size_t a : actions) {
    const Action& action = c.actions.at(a);
    ActionBindings bindings = bind_action(c.skeleton, action);
    SamplingCursor cursor;
    reset_cursor(action, &cursor);
    std::vector<float> times;
    for (const Channel& channel : action.channels)
      times.insert(times.end(), channel.times.begin(), channel.times.end());
    for (int i = 0; i <= samples_per_action; ++i)
      times.push_back(action.start +
                      action.duration() * static_cast<float>(i) / static_cast<float>(samples_per_action));
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    // Keys can be many (baked animations): a few hundred poses bound the box well.
    size_t step = std::max<size_t>(1, times.size() / 512);
    for (size_t i = 0; i < times.size(); i += step) {
      reset_to_rest(c.skeleton, &local);
      run_job(SamplingJob{&action, times[i], bindings.targets, &cursor, &local}, "SamplingJob");
      grow_by_pose(c, plan, local, model, palette, positions, normals, box);
    }
  }
  glm::vec3 pad(glm::length(box.size()) * padding);
  box.min -= pad;
  box.max += pad;
  return box;
}

}  // namespace

Aabb animated_bounds(const Character& c, int samples_per_action, float padding) {
  std::vector<size_t> every(c.actions.size());
  for (size_t a = 0; a < every.size(); ++a) every[a] = a;
  return bounds_of_poses(c, every, true, samples_per_action, padding);
}

Aabb action_bounds(const Character& c, size_t action, int samples_per_action, float padding) {
  const size_t one[] = {action};
  return bounds_of_poses(c, c.actions.empty() ? std::span<const size_t>() : std::span<const size_t>(one), false,
                         samples_per_action, padding);
}

Aabb bind_pose_bounds(const Character& c) {
  if (c.mesh.positions.empty()) return Aabb{};
  Aabb box{c.mesh.positions.front(), c.mesh.positions.front()};
  for (const glm::vec3& p : c.mesh.positions) {
    box.min = glm::min(box.min, p);
    box.max = glm::max(box.max, p);
  }
  return box;
}

}  // namespace crowdprof

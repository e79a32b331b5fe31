#include "animation/bake.h"
#include "animation/run_job.h"

#include <algorithm>
#include <cmath>

#include "animation/pose.h"

namespace crowdprof {

size_t baked_intervals(const Action& action, float rate_hz) {
  double samples = static_cast<double>(action.duration()) * static_cast<double>(rate_hz);
  // A duration that is a whole number of intervals in exact arithmetic must not
  // gain one from rounding (1 s at 30 Hz: 30, not 31).
  double intervals = std::ceil(samples - 1e-4);
  return intervals >= 1.0 && std::isfinite(intervals) ? static_cast<size_t>(intervals) : 1;
}

float baked_position(const Action& action, size_t intervals, float time) {
  float duration = action.duration();
  if (!(duration > 0.0f)) return 0.0f;
  float t = std::clamp(time, action.start, action.end);
  return std::clamp((t - action.start) / duration * static_cast<float>(intervals), 0.0f, static_cast<float>(intervals));
}

bool BakeJob::Validate() const {
  if (!skeleton || !action || !cursor || !pose) return false;
  if (!std::isfinite(rate_hz) || !(rate_hz > 0.0f)) return false;
  size_t joints = skeleton->joint_count();
  return targets.size() == action->channels.size() && model.size() == joints && pose->joint_count() == joints &&
         cursor->keys.size() == action->channels.size() && output.size() == baked_samples(*action, rate_hz) * joints;
}

bool BakeJob::Run() const {
  if (!Validate()) return false;
  size_t joints = skeleton->joint_count(), intervals = baked_intervals(*action, rate_hz);
  for (size_t s = 0; s <= intervals; ++s) {
    // The last sample is the last key exactly, not start + intervals x step.
    float time = s == intervals
                     ? action->end
                     : action->start + action->duration() * static_cast<float>(s) / static_cast<float>(intervals);
    reset_to_rest(*skeleton, pose);  // joints the action leaves alone stand at rest (no allocation: sized)
    run_job(SamplingJob{action, time, targets, cursor, pose}, "SamplingJob");
    run_job(LocalToModelJob{skeleton, pose, model}, "LocalToModelJob");
    run_job(SkinningMatricesJob{skeleton, model, output.subspan(s * joints, joints)}, "SkinningMatricesJob");
  }
  return true;
}

bool BakedPaletteJob::Validate() const {
  return joints > 0 && baked.size() % joints == 0 && baked.size() / joints >= 2 && std::isfinite(position) &&
         output.size() == joints;
}

bool BakedPaletteJob::Run() const {
  if (!Validate()) return false;
  size_t last_interval = baked.size() / joints - 2;
  float u = std::max(position, 0.0f);
  size_t first = std::min(static_cast<size_t>(u), last_interval);
  float w = std::min(u - static_cast<float>(first), 1.0f);
  const SkinMatrix* a = &baked[first * joints];
  const SkinMatrix* b = a + joints;
  for (size_t j = 0; j < joints; ++j) output[j] = a[j] * (1.0f - w) + b[j] * w;
  return true;
}

bool BakedFadeJob::Validate() const {
  return now.Validate() && from.Validate() && now.joints == from.joints && now.output.data() != from.output.data() &&
         from_weight >= 0.0f && from_weight <= 1.0f;
}

bool BakedFadeJob::Run() const {
  if (!Validate() || !now.Run() || !from.Run()) return false;
  for (size_t j = 0; j < now.joints; ++j)
    now.output[j] = now.output[j] * (1.0f - from_weight) + from.output[j] * from_weight;
  return true;
}

}  // namespace crowdprof

namespace crowdprof {

bool bake_character(const Character& character, std::span<const std::span<const int32_t>> targets, float rate_hz,
                    BakedCharacter* out) {
  if (!out || targets.size() != character.actions.size()) return false;
  const Skeleton& skeleton = character.skeleton;
  BakedCharacter baked;
  baked.rate_hz = rate_hz;
  baked.joints = skeleton.joint_count();
  size_t samples = 0;
  for (const Action& action : character.actions) {
    baked.first_sample.push_back(samples);
    baked.intervals.push_back(baked_intervals(action, rate_hz));
    samples += baked.intervals.back() + 1;
  }
  baked.matrices.resize(samples * baked.joints);
  LocalPose pose;
  reset_to_rest(skeleton, &pose);
  std::vector<glm::mat4> model(baked.joints);
  SamplingCursor cursor;
  for (size_t a = 0; a < character.actions.size(); ++a) {
    const Action& action = character.actions[a];
    reset_cursor(action, &cursor);
    std::span<SkinMatrix> output =
        std::span(baked.matrices)
            .subspan(baked.first_sample[a] * baked.joints, (baked.intervals[a] + 1) * baked.joints);
    if (!BakeJob{&skeleton, &action, targets[a], rate_hz, &cursor, &pose, model, output}.Run()) return false;
  }
  *out = std::move(baked);
  return true;
}

}  // namespace crowdprof

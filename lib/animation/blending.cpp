#include "animation/blending.h"

#include <cmath>

#include "animation/blending_kernels.h"

namespace crowdprof {

namespace {

bool sized_like(const LocalPose& pose, size_t joints) {
  return pose.translations.size() == joints && pose.rotations.size() == joints && pose.scales.size() == joints;
}

bool layer_fits(const BlendLayer& layer, size_t joints) {
  return layer.pose && sized_like(*layer.pose, joints) && layer.weight >= 0.0f && std::isfinite(layer.weight) &&
         (layer.joint_weights.empty() || layer.joint_weights.size() == joints);
}

bool masked(std::span<const BlendLayer> layers) {
  for (const BlendLayer& layer : layers)
    if (!layer.joint_weights.empty()) return true;
  return false;
}

// Layer's weight at joint j: its own, times its mask's share there.
float weight_at(const BlendLayer& layer, size_t j) {
  return layer.joint_weights.empty() ? layer.weight : layer.weight * layer.joint_weights[j];
}

// Joint j blended one joint at a time: the joints after the kernel's last
// whole group. The kernels do the same operations in the same order; with no
// mask every joint's sum is the job's (BlendingJob::Run), summed the same way.
void blend_one_joint(const BlendKernelArgs& args, float threshold, size_t j) {
  glm::vec3 translation(0.0f), scale(0.0f);
  glm::quat rotation(0.0f, 0.0f, 0.0f, 0.0f);
  float total = 0.0f;
  auto add = [&](const LocalPose& pose, float weight) {
    translation += weight * pose.translations[j];
    scale += weight * pose.scales[j];
    const glm::quat& q = pose.rotations[j];
    rotation += glm::dot(rotation, q) < 0.0f ? -weight * q : weight * q;
  };
  for (const BlendLayer& layer : args.layers) {
    if (!(layer.weight > 0.0f)) continue;
    const float weight = weight_at(layer, j);
    if (!(weight > 0.0f)) continue;
    add(*layer.pose, weight);
    total += weight;
  }
  if (total < threshold) {
    const float rest_weight = threshold - total;
    add(*args.rest, rest_weight);
    total += rest_weight;
  }
  const float inverse_total = 1.0f / total;
  LocalPose& out = *args.output;
  out.translations[j] = translation * inverse_total;
  out.scales[j] = scale * inverse_total;
  out.rotations[j] = rotation * (1.0f / std::sqrt(glm::dot(rotation, rotation)));
}

// out = out + a share of delta (blending.h's additive rule) at joint j.
void add_one_joint(const LocalPose& delta, float weight, size_t j, LocalPose& out) {
  out.translations[j] += weight * delta.translations[j];
  glm::quat d = delta.rotations[j];
  if (d.w < 0.0f) d = -d;
  const glm::quat partial(1.0f + weight * (d.w - 1.0f), weight * d.x, weight * d.y, weight * d.z);
  out.rotations[j] = glm::normalize(out.rotations[j] * glm::normalize(partial));
  out.scales[j] *= glm::vec3(1.0f) + weight * (delta.scales[j] - glm::vec3(1.0f));
}

}  // namespace

bool BlendingJob::Validate() const {
  if (!rest || !output || layers.empty() || !(threshold > 0.0f) || !std::isfinite(threshold)) return false;
  const size_t joints = rest->joint_count();
  if (!sized_like(*rest, joints) || !sized_like(*output, joints)) return false;
  for (const BlendLayer& layer : layers)
    if (!layer_fits(layer, joints)) return false;
  for (const BlendLayer& layer : additive_layers)
    if (!layer_fits(layer, joints) || layer.pose == output) return false;
  return true;
}

bool BlendingJob::Run() const {
  if (!Validate()) return false;
  BlendKernelArgs args{layers, rest, false, 0.0f, 0.0f, output, threshold};
  const size_t joints = rest->joint_count();
  size_t done = 0;
  if (masked(layers)) {
    done = blend_masked_joint_groups(args);
  } else {
    // The weights are the job's, not a joint's: summed once, in layer order.
    float total = 0.0f;
    for (const BlendLayer& layer : layers)
      if (layer.weight > 0.0f) total += layer.weight;
    if (total < threshold) {
      args.fill_rest = true;
      args.rest_weight = threshold - total;
      total += args.rest_weight;
    }
    args.inverse_total = 1.0f / total;
    done = blend_joint_groups(args);
  }
  for (size_t j = done; j < joints; ++j) blend_one_joint(args, threshold, j);
  for (const BlendLayer& layer : additive_layers) {
    if (!(layer.weight > 0.0f)) continue;
    for (size_t j = 0; j < joints; ++j) {
      const float weight = weight_at(layer, j);
      if (weight > 0.0f) add_one_joint(*layer.pose, weight, j, *output);
    }
  }
  return true;
}

void additive_delta(const LocalPose& pose, const LocalPose& reference, LocalPose* delta) {
  const size_t joints = pose.joint_count();
  delta->translations.resize(joints);
  delta->rotations.resize(joints);
  delta->scales.resize(joints);
  for (size_t j = 0; j < joints; ++j) {
    delta->translations[j] = pose.translations[j] - reference.translations[j];
    delta->rotations[j] = glm::conjugate(reference.rotations[j]) * pose.rotations[j];
    delta->scales[j] = pose.scales[j] / reference.scales[j];
  }
}

}  // namespace crowdprof

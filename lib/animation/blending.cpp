#include "animation/blending.h"

#include <cmath>

#include "animation/blending_kernels.h"

namespace crowdprof {

namespace {

bool sized_like(const LocalPose& pose, size_t joints) {
  return pose.translations.size() == joints && pose.rotations.size() == joints && pose.scales.size() == joints;
}

// Joint j blended one joint at a time: the joints after the kernel's last
// whole group. The kernel does the same operations in the same order.
void blend_one_joint(const BlendKernelArgs& args, size_t j) {
  glm::vec3 translation(0.0f), scale(0.0f);
  glm::quat rotation(0.0f, 0.0f, 0.0f, 0.0f);
  auto add = [&](const LocalPose& pose, float weight) {
    translation += weight * pose.translations[j];
    scale += weight * pose.scales[j];
    const glm::quat& q = pose.rotations[j];
    rotation += glm::dot(rotation, q) < 0.0f ? -weight * q : weight * q;
  };
  for (const BlendLayer& layer : args.layers)
    if (layer.weight > 0.0f) add(*layer.pose, layer.weight);
  if (args.fill_rest) add(*args.rest, args.rest_weight);
  LocalPose& out = *args.output;
  out.translations[j] = translation * args.inverse_total;
  out.scales[j] = scale * args.inverse_total;
  out.rotations[j] = rotation * (1.0f / std::sqrt(glm::dot(rotation, rotation)));
}

}  // namespace

bool BlendingJob::Validate() const {
  if (!rest || !output || layers.empty() || !(threshold > 0.0f) || !std::isfinite(threshold)) return false;
  const size_t joints = rest->joint_count();
  if (!sized_like(*rest, joints) || !sized_like(*output, joints)) return false;
  for (const BlendLayer& layer : layers)
    if (!layer.pose || !sized_like(*layer.pose, joints) || !(layer.weight >= 0.0f) || !std::isfinite(layer.weight))
      return false;
  return true;
}

bool BlendingJob::Run() const {
  if (!Validate()) return false;
  // The weights are the job's, not a joint's: summed once, in layer order.
  BlendKernelArgs args{layers, rest, false, 0.0f, 0.0f, output};
  float total = 0.0f;
  for (const BlendLayer& layer : layers)
    if (layer.weight > 0.0f) total += layer.weight;
  if (total < threshold) {
    args.fill_rest = true;
    args.rest_weight = threshold - total;
    total += args.rest_weight;
  }
  args.inverse_total = 1.0f / total;
  const size_t joints = rest->joint_count();
  for (size_t j = blend_joint_groups(args); j < joints; ++j) blend_one_joint(args, j);
  return true;
}

}  // namespace crowdprof

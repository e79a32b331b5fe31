#include "animation/blending.h"

#include <cmath>

namespace crowdprof {

namespace {

bool sized_like(const LocalPose& pose, size_t joints) {
  return pose.translations.size() == joints && pose.rotations.size() == joints && pose.scales.size() == joints;
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
  const size_t joints = rest->joint_count();
  // Joint by joint, so that the output may be one of the layers: each joint's
  // inputs are read before its output is written.
  for (size_t j = 0; j < joints; ++j) {
    glm::vec3 translation(0.0f), scale(0.0f);
    glm::quat rotation(0.0f, 0.0f, 0.0f, 0.0f);
    float total = 0.0f;
    auto add = [&](const LocalPose& pose, float weight) {
      translation += weight * pose.translations[j];
      scale += weight * pose.scales[j];
      const glm::quat& q = pose.rotations[j];
      rotation += glm::dot(rotation, q) < 0.0f ? -weight * q : weight * q;
      total += weight;
    };
    for (const BlendLayer& layer : layers)
      if (layer.weight > 0.0f) add(*layer.pose, layer.weight);
    if (total < threshold) add(*rest, threshold - total);
    const float inverse = 1.0f / total;
    output->translations[j] = translation * inverse;
    output->scales[j] = scale * inverse;
    output->rotations[j] = rotation * (1.0f / std::sqrt(glm::dot(rotation, rotation)));
  }
  return true;
}

}  // namespace crowdprof

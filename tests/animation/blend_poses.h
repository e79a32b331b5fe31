// Random poses and a double-precision blend written from blending.h's
// contract, for the blend job's tests (blending_simd_test, blending_layers_test).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <span>

#include <glm/gtc/quaternion.hpp>

#include "animation/blending.h"

namespace crowdprof {

inline LocalPose random_blend_pose(size_t joints, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), scale(0.5f, 1.5f);
  LocalPose p;
  for (size_t j = 0; j < joints; ++j) {
    p.translations.emplace_back(unit(rng), unit(rng), unit(rng));
    p.scales.emplace_back(scale(rng), scale(rng), scale(rng));
    glm::quat q(unit(rng), unit(rng), unit(rng), unit(rng));  // w, x, y, z; either sign
    p.rotations.push_back(glm::normalize(q));
  }
  return p;
}

// The blend in double precision, masks included.
inline LocalPose reference_blend(std::span<const BlendLayer> layers, const LocalPose& rest, float threshold) {
  LocalPose out = rest;
  for (size_t j = 0; j < rest.joint_count(); ++j) {
    glm::dvec3 t(0.0), s(0.0);
    glm::dvec4 q(0.0);  // x y z w
    double total = 0.0;
    auto add = [&](const LocalPose& pose, double w) {
      t += w * glm::dvec3(pose.translations[j]);
      s += w * glm::dvec3(pose.scales[j]);
      const glm::quat& r = pose.rotations[j];
      const glm::dvec4 v(r.x, r.y, r.z, r.w);
      q += glm::dot(q, v) < 0.0 ? -w * v : w * v;
      total += w;
    };
    for (const BlendLayer& layer : layers) {
      const double w = double(layer.weight) * (layer.joint_weights.empty() ? 1.0 : layer.joint_weights[j]);
      if (w > 0.0) add(*layer.pose, w);
    }
    if (total < threshold) add(rest, threshold - total);
    out.translations[j] = glm::vec3(t / total);
    out.scales[j] = glm::vec3(s / total);
    const glm::dvec4 n = q / glm::length(q);
    out.rotations[j] = glm::quat(float(n.w), float(n.x), float(n.y), float(n.z));
  }
  return out;
}

// Largest difference of any component (a rotation's either sign the same).
inline float largest_blend_gap(const LocalPose& a, const LocalPose& b) {
  float gap = 0.0f;
  for (size_t j = 0; j < a.joint_count(); ++j)
    for (int c = 0; c < 4; ++c) {
      if (c < 3) {
        gap = std::max(gap, std::fabs(a.translations[j][c] - b.translations[j][c]));
        gap = std::max(gap, std::fabs(a.scales[j][c] - b.scales[j][c]));
      }
      gap = std::max(gap, std::min(std::fabs(a.rotations[j][c] - b.rotations[j][c]),
                                   std::fabs(a.rotations[j][c] + b.rotations[j][c])));
    }
  return gap;
}

inline bool same_joint_bits(const LocalPose& a, const LocalPose& b, size_t j) {
  return std::memcmp(&a.translations[j], &b.translations[j], sizeof(glm::vec3)) == 0 &&
         std::memcmp(&a.scales[j], &b.scales[j], sizeof(glm::vec3)) == 0 &&
         std::memcmp(&a.rotations[j], &b.rotations[j], sizeof(glm::quat)) == 0;
}

inline bool same_bits(const LocalPose& a, const LocalPose& b) {
  if (a.joint_count() != b.joint_count()) return false;
  for (size_t j = 0; j < a.joint_count(); ++j)
    if (!same_joint_bits(a, b, j)) return false;
  return true;
}

}  // namespace crowdprof

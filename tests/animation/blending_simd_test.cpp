// The blend job four joints at a time (lib/animation/blending_kernels.cpp), at
// every SIMD target this CPU runs: within 1e-6 of a double-precision blend on
// random poses (joint counts not a multiple of four, weights 0 and 1, the rest
// pose filling in, output in place), and the same bits on every target.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "animation/blending.h"
#include "skinning/simd_target.h"

namespace crowdprof {
namespace {

LocalPose random_blend_pose(size_t joints, std::mt19937& rng) {
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

// The blend in double precision, written from blending.h's contract.
LocalPose reference_blend(std::span<const BlendLayer> layers, const LocalPose& rest, float threshold) {
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
    for (const BlendLayer& layer : layers)
      if (layer.weight > 0.0f) add(*layer.pose, layer.weight);
    if (total < threshold) add(rest, threshold - total);
    out.translations[j] = glm::vec3(t / total);
    out.scales[j] = glm::vec3(s / total);
    const glm::dvec4 n = q / glm::length(q);
    out.rotations[j] =
        glm::quat(static_cast<float>(n.w), static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z));
  }
  return out;
}

// Largest difference of any component.
float largest_blend_gap(const LocalPose& a, const LocalPose& b) {
  float gap = 0.0f;
  for (size_t j = 0; j < a.joint_count(); ++j)
    for (int c = 0; c < 4; ++c) {
      if (c < 3) {
        gap = std::max(gap, std::fabs(a.translations[j][c] - b.translations[j][c]));
        gap = std::max(gap, std::fabs(a.scales[j][c] - b.scales[j][c]));
      }
      gap = std::max(gap, std::fabs(a.rotations[j][c] - b.rotations[j][c]));
    }
  return gap;
}

bool same_bits(const LocalPose& a, const LocalPose& b) {
  const size_t n = a.joint_count();
  return n == b.joint_count() &&
         std::memcmp(a.translations.data(), b.translations.data(), n * sizeof(glm::vec3)) == 0 &&
         std::memcmp(a.scales.data(), b.scales.data(), n * sizeof(glm::vec3)) == 0 &&
         std::memcmp(a.rotations.data(), b.rotations.data(), n * sizeof(glm::quat)) == 0;
}

// Each test runs every target, then TearDown goes back to the best.
struct BlendSimd : ::testing::Test {
  void TearDown() override { EXPECT_EQ("", force_simd_target("")); }
};

// Weight sets: a crossfade's two, one alone, 0 and 1, three layers, and
// some that add up to less than the threshold (the rest pose fills in).
const std::vector<std::vector<float>> kBlendWeightSets = {{0.3f, 0.7f},       {1.0f, 0.0f},   {0.0f, 1.0f}, {1.0f},
                                                          {0.2f, 0.5f, 0.9f}, {0.03f, 0.04f}, {0.0f, 0.0f}, {0.05f},
                                                          {0.5f, 0.0f, 0.5f}};

TEST_F(BlendSimd, EveryTargetIsWithinAMillionthOfTheReferenceAndGivesTheSameBits) {
  const float threshold = 0.1f;
  // Once: a forced target narrows what available_simd_targets() lists.
  const std::vector<std::string> targets = available_simd_targets();
  for (size_t joints : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 13u, 69u}) {
    std::mt19937 rng(static_cast<unsigned>(joints));
    const LocalPose rest = random_blend_pose(joints, rng);
    std::vector<LocalPose> poses;
    for (int i = 0; i < 3; ++i) poses.push_back(random_blend_pose(joints, rng));
    for (const std::vector<float>& weights : kBlendWeightSets) {
      std::vector<BlendLayer> layers;
      for (size_t i = 0; i < weights.size(); ++i) layers.push_back({&poses[i], weights[i]});
      const LocalPose expected = reference_blend(layers, rest, threshold);
      LocalPose first;
      for (const std::string& target : targets) {
        ASSERT_EQ("", force_simd_target(target));
        LocalPose out = rest;
        ASSERT_TRUE((BlendingJob{layers, &rest, threshold, &out}.Run()));
        const std::string where =
            target + ", " + std::to_string(joints) + " joints, weights " + testing::PrintToString(weights);
        EXPECT_LT(largest_blend_gap(out, expected), 1e-6f) << where;
        if (first.joint_count() == 0)
          first = out;
        else
          EXPECT_TRUE(same_bits(out, first)) << where << ": not the first target's bits";
      }
    }
  }
}

TEST_F(BlendSimd, WeightsZeroAndOneGiveTheSinglePoseAtEveryTarget) {
  std::mt19937 rng(53);
  const LocalPose rest = random_blend_pose(11, rng), a = random_blend_pose(11, rng), b = random_blend_pose(11, rng);
  const std::vector<std::string> targets = available_simd_targets();
  for (const std::string& target : targets) {
    ASSERT_EQ("", force_simd_target(target));
    for (float weight : {0.0f, 1.0f}) {
      const BlendLayer layers[] = {{&a, 1.0f - weight}, {&b, weight}};
      LocalPose out = rest;
      ASSERT_TRUE((BlendingJob{layers, &rest, 0.1f, &out}.Run()));
      const LocalPose& single = weight == 0.0f ? a : b;
      for (size_t j = 0; j < 11; ++j) {
        EXPECT_EQ(out.translations[j], single.translations[j]) << target << " joint " << j;
        EXPECT_EQ(out.scales[j], single.scales[j]) << target << " joint " << j;
        // The sign a layer's quaternion comes with is kept: it is the first one added.
        for (int c = 0; c < 4; ++c)
          EXPECT_NEAR(out.rotations[j][c], single.rotations[j][c], 1e-6) << target << " joint " << j;
      }
    }
  }
}

TEST_F(BlendSimd, InPlaceGivesWhatASeparateOutputGets) {
  std::mt19937 rng(7);
  const LocalPose rest = random_blend_pose(9, rng);
  LocalPose a = random_blend_pose(9, rng);
  const LocalPose b = random_blend_pose(9, rng);
  const std::vector<std::string> targets = available_simd_targets();
  for (const std::string& target : targets) {
    ASSERT_EQ("", force_simd_target(target));
    LocalPose layer = a, apart = rest;
    const BlendLayer layers[] = {{&layer, 0.4f}, {&b, 0.6f}};
    ASSERT_TRUE((BlendingJob{layers, &rest, 0.1f, &apart}.Run()));
    ASSERT_TRUE((BlendingJob{layers, &rest, 0.1f, &layer}.Run()));
    EXPECT_TRUE(same_bits(layer, apart)) << target;
  }
}

}  // namespace
}  // namespace crowdprof

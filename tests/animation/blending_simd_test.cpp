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

#include "animation/blend_poses.h"
#include "animation/blending.h"
#include "skinning/simd_target.h"

namespace crowdprof {
namespace {

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

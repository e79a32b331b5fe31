// The blend job's layers (lib/animation/blending.h, issue 56): masks per joint
// at every SIMD target (within 1e-6 of a double-precision blend, the same bits
// on every target, a mask of ones the bits of none, joints outside a mask
// untouched bit for bit) and additive layers (a delta of the reference frame
// changes nothing, a whole delta lands on its pose).
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

// A mask with zeros, ones and shares between.
std::vector<float> random_mask(size_t joints, std::mt19937& rng) {
  std::uniform_int_distribution<int> kind(0, 3);
  std::uniform_real_distribution<float> share(0.0f, 1.0f);
  std::vector<float> mask;
  for (size_t j = 0; j < joints; ++j) {
    const int k = kind(rng);
    mask.push_back(k == 0 ? 0.0f : k == 1 ? 1.0f : share(rng));
  }
  return mask;
}

LocalPose run_blend(std::span<const BlendLayer> layers, const LocalPose& rest,
                    std::span<const BlendLayer> additive = {}) {
  LocalPose out = rest;
  BlendingJob job;
  job.layers = layers;
  job.rest = &rest;
  job.output = &out;
  job.additive_layers = additive;
  EXPECT_TRUE(job.Run());
  return out;
}

struct BlendLayers : ::testing::Test {
  void TearDown() override { EXPECT_EQ("", force_simd_target("")); }
  const std::vector<std::string> targets = available_simd_targets();
};

const size_t kLayerJointCounts[] = {1, 3, 4, 5, 8, 13, 69};

TEST_F(BlendLayers, MasksAreWithinAMillionthOfTheReferenceWithTheSameBitsOnEveryTarget) {
  for (size_t joints : kLayerJointCounts) {
    std::mt19937 rng(static_cast<unsigned>(100 + joints));
    const LocalPose rest = random_blend_pose(joints, rng);
    const LocalPose a = random_blend_pose(joints, rng), b = random_blend_pose(joints, rng),
                    c = random_blend_pose(joints, rng);
    for (int trial = 0; trial < 4; ++trial) {
      const std::vector<float> ma = random_mask(joints, rng), mc = random_mask(joints, rng);
      // A masked layer, an unmasked one, a faint masked one (the rest pose
      // fills in where only it weighs).
      const BlendLayer layers[] = {{&a, 0.8f, ma}, {&b, trial == 0 ? 0.0f : 0.3f}, {&c, 0.05f, mc}};
      const LocalPose expected = reference_blend(layers, rest, 0.1f);
      LocalPose first;
      for (const std::string& target : targets) {
        ASSERT_EQ("", force_simd_target(target));
        const LocalPose out = run_blend(layers, rest);
        const std::string where = target + ", " + std::to_string(joints) + " joints, trial " + std::to_string(trial);
        EXPECT_LT(largest_blend_gap(out, expected), 1e-6f) << where;
        if (first.joint_count() == 0)
          first = out;
        else
          EXPECT_TRUE(same_bits(out, first)) << where << ": not the first target's bits";
      }
    }
  }
}

TEST_F(BlendLayers, AMaskOfOnesGivesTheBitsOfNoMask) {
  for (size_t joints : kLayerJointCounts) {
    std::mt19937 rng(static_cast<unsigned>(joints));
    const LocalPose rest = random_blend_pose(joints, rng), a = random_blend_pose(joints, rng),
                    b = random_blend_pose(joints, rng);
    const std::vector<float> ones(joints, 1.0f);
    for (const std::string& target : targets) {
      ASSERT_EQ("", force_simd_target(target));
      for (float wa : {0.3f, 0.04f}) {
        const BlendLayer plain[] = {{&a, wa}, {&b, 0.7f - wa}};
        const BlendLayer masked[] = {{&a, wa, ones}, {&b, 0.7f - wa}};
        EXPECT_TRUE(same_bits(run_blend(plain, rest), run_blend(masked, rest))) << target << " " << joints;
      }
    }
  }
}

// An action laid over the upper body: the base takes 1 - m, the action m.
TEST_F(BlendLayers, JointsOutsideAMaskAreUntouchedBitForBitAndInsideItTheLayerRules) {
  for (size_t joints : kLayerJointCounts) {
    std::mt19937 rng(static_cast<unsigned>(7 * joints));
    const LocalPose rest = random_blend_pose(joints, rng), walk = random_blend_pose(joints, rng),
                    wave = random_blend_pose(joints, rng);
    std::vector<float> upper(joints), lower(joints);
    for (size_t j = 0; j < joints; ++j) {
      upper[j] = j % 3 == 0 ? 0.0f : j % 3 == 1 ? 1.0f : 0.5f;
      lower[j] = 1.0f - upper[j];
    }
    const BlendLayer alone[] = {{&walk, 1.0f}};
    const BlendLayer wave_alone[] = {{&wave, 1.0f}};
    const BlendLayer layered[] = {{&walk, 1.0f, lower}, {&wave, 1.0f, upper}};
    for (const std::string& target : targets) {
      ASSERT_EQ("", force_simd_target(target));
      const LocalPose base = run_blend(alone, rest), top = run_blend(wave_alone, rest);
      const LocalPose out = run_blend(layered, rest);
      for (size_t j = 0; j < joints; ++j) {
        const LocalPose* expected = upper[j] == 0.0f ? &base : upper[j] == 1.0f ? &top : nullptr;
        if (expected) {
          EXPECT_TRUE(same_joint_bits(out, *expected, j)) << target << " joint " << j;
        } else {
          EXPECT_FALSE(same_joint_bits(out, base, j)) << target << " joint " << j;
        }
      }
      // Weight 0 is the base, whatever its mask.
      const BlendLayer faded_out[] = {{&walk, 1.0f}, {&wave, 0.0f, upper}};
      EXPECT_TRUE(same_bits(run_blend(faded_out, rest), base)) << target;
    }
  }
}

TEST(BlendAdditive, ADeltaOfItsOwnReferenceFrameChangesNothing) {
  std::mt19937 rng(56);
  const LocalPose rest = random_blend_pose(13, rng), walk = random_blend_pose(13, rng),
                  breath = random_blend_pose(13, rng);
  LocalPose delta;
  additive_delta(breath, breath, &delta);
  const BlendLayer base[] = {{&walk, 1.0f}};
  const LocalPose plain = run_blend(base, rest);
  for (float weight : {0.5f, 1.0f}) {
    const BlendLayer add[] = {{&delta, weight}};
    EXPECT_LT(largest_blend_gap(run_blend(base, rest, add), plain), 1e-6f) << weight;
  }
  // Weight 0, or a mask of zeros, leaves the bits alone.
  LocalPose moved;
  additive_delta(walk, breath, &moved);
  const std::vector<float> zeros(13, 0.0f);
  const BlendLayer none[] = {{&moved, 0.0f}, {&moved, 1.0f, zeros}};
  EXPECT_TRUE(same_bits(run_blend(base, rest, none), plain));
}

TEST(BlendAdditive, AWholeDeltaOnItsReferenceGivesItsPoseAndAMaskKeepsItToItsJoints) {
  std::mt19937 rng(57);
  const LocalPose rest = random_blend_pose(9, rng), reference = random_blend_pose(9, rng),
                  lean = random_blend_pose(9, rng);
  LocalPose delta;
  additive_delta(lean, reference, &delta);
  const BlendLayer base[] = {{&reference, 1.0f}};
  const BlendLayer add[] = {{&delta, 1.0f}};
  EXPECT_LT(largest_blend_gap(run_blend(base, rest, add), lean), 1e-5f);
  std::vector<float> spine(9, 0.0f);
  spine[4] = spine[5] = 1.0f;
  const BlendLayer masked[] = {{&delta, 1.0f, spine}};
  const LocalPose out = run_blend(base, rest, masked), plain = run_blend(base, rest);
  for (size_t j = 0; j < 9; ++j) {
    if (spine[j] == 0.0f)
      EXPECT_TRUE(same_joint_bits(out, plain, j)) << j;
    else
      EXPECT_LT(glm::length(out.translations[j] - lean.translations[j]), 1e-5f) << j;
  }
}

TEST(BlendAdditive, HalfADeltaGoesHalfTheWay) {
  LocalPose zero;
  zero.translations = {glm::vec3(0.0f)};
  zero.rotations = {glm::quat(1, 0, 0, 0)};
  zero.scales = {glm::vec3(1.0f)};
  LocalPose turned = zero;
  turned.translations[0] = glm::vec3(2, 0, 0);
  turned.rotations[0] = glm::angleAxis(glm::radians(60.0f), glm::vec3(0, 0, 1));
  turned.scales[0] = glm::vec3(3.0f);
  LocalPose delta;
  additive_delta(turned, zero, &delta);
  const BlendLayer base[] = {{&zero, 1.0f}};
  const BlendLayer half[] = {{&delta, 0.5f}};
  const LocalPose out = run_blend(base, zero, half);
  EXPECT_NEAR(out.translations[0].x, 1.0f, 1e-6);
  EXPECT_NEAR(out.scales[0].y, 2.0f, 1e-6);
  // Normalised lerp from identity: 30 degrees at the midpoint of a 60 degree turn.
  EXPECT_NEAR(glm::degrees(glm::angle(out.rotations[0])), 30.0f, 1e-3);
}

TEST(BlendAdditive, RefusesMasksOfTheWrongSizeAndAnAdditiveLayerThatIsTheOutput) {
  std::mt19937 rng(58);
  const LocalPose rest = random_blend_pose(5, rng);
  LocalPose a = random_blend_pose(5, rng), out = rest;
  const std::vector<float> short_mask(4, 1.0f);
  const BlendLayer bad_mask[] = {{&a, 1.0f, short_mask}};
  EXPECT_FALSE((BlendingJob{bad_mask, &rest, 0.1f, &out}.Run()));
  const BlendLayer fine[] = {{&a, 1.0f}};
  BlendingJob job{fine, &rest, 0.1f, &out};
  EXPECT_TRUE(job.Validate());
  const BlendLayer onto_output[] = {{&out, 1.0f}};
  job.additive_layers = onto_output;
  EXPECT_FALSE(job.Validate());
  job.additive_layers = bad_mask;
  EXPECT_FALSE(job.Validate());
}

}  // namespace
}  // namespace crowdprof

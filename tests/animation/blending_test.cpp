// The blend job (lib/animation/blending.h): weights 0 and 1 give a pose back,
// the mean of two poses is slerp's midpoint, a quaternion's sign does not
// matter, the rest pose fills in below the threshold, the output may be a
// layer, and bad inputs are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/gtc/quaternion.hpp>

#include "animation/blending.h"
#include "animation/sampling.h"

namespace crowdprof {
namespace {

LocalPose pose_of(std::initializer_list<glm::vec3> translations, std::initializer_list<glm::quat> rotations,
                  std::initializer_list<glm::vec3> scales) {
  LocalPose p;
  p.translations = translations;
  p.rotations = rotations;
  p.scales = scales;
  return p;
}

glm::quat about_y(float degrees) {
  return glm::angleAxis(glm::radians(degrees), glm::vec3(0, 1, 0));
}

// The angle between two rotations, whatever their quaternions' signs (by the
// difference's axis part: acos of a dot near 1 would lose the small angles).
float degrees_between(const glm::quat& a, const glm::quat& b) {
  const glm::quat d = glm::conjugate(a) * b;
  return glm::degrees(2.0f * std::atan2(glm::length(glm::vec3(d.x, d.y, d.z)), std::fabs(d.w)));
}

struct Poses {
  LocalPose rest =
      pose_of({{0, 0, 0}, {0, 1, 0}}, {glm::quat(1, 0, 0, 0), glm::quat(1, 0, 0, 0)}, {{1, 1, 1}, {1, 1, 1}});
  LocalPose a = pose_of({{1, 0, 0}, {0, 2, 0}}, {about_y(10), about_y(-40)}, {{1, 1, 1}, {2, 2, 2}});
  LocalPose b = pose_of({{3, 0, 0}, {0, 2, 4}}, {about_y(70), about_y(50)}, {{1, 1, 1}, {1, 1, 1}});
  LocalPose out = rest;
};

LocalPose blend(const LocalPose& rest, std::span<const BlendLayer> layers) {
  LocalPose out = rest;
  BlendingJob job;
  job.layers = layers;
  job.rest = &rest;
  job.output = &out;
  EXPECT_TRUE(job.Run());
  return out;
}

TEST(Blending, WeightOneGivesThePoseBackAndZeroLeavesALayerOut) {
  Poses p;
  const BlendLayer only_b[] = {{&p.a, 0.0f}, {&p.b, 1.0f}};
  const LocalPose out = blend(p.rest, only_b);
  for (size_t j = 0; j < 2; ++j) {
    EXPECT_EQ(out.translations[j], p.b.translations[j]) << j;
    EXPECT_EQ(out.scales[j], p.b.scales[j]) << j;
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(out.rotations[j][c], p.b.rotations[j][c], 1e-6) << j;
  }
}

TEST(Blending, HalfAndHalfIsTheMeanAndSlerpsMidpoint) {
  Poses p;
  const BlendLayer half[] = {{&p.a, 0.5f}, {&p.b, 0.5f}};
  const LocalPose out = blend(p.rest, half);
  EXPECT_NEAR(out.translations[0].x, 2.0f, 1e-6);
  EXPECT_NEAR(out.scales[1].x, 1.5f, 1e-6);
  for (size_t j = 0; j < 2; ++j) {
    const glm::quat mid = slerp_shortest(p.a.rotations[j], p.b.rotations[j], 0.5f);
    EXPECT_LT(degrees_between(out.rotations[j], mid), 1e-4) << j;
    EXPECT_NEAR(glm::length(out.rotations[j]), 1.0f, 1e-6) << j;
  }
}

TEST(Blending, AQuaternionsSignDoesNotMatter) {
  Poses p;
  LocalPose flipped = p.b;
  for (glm::quat& q : flipped.rotations) q = -q;
  const BlendLayer one[] = {{&p.a, 0.3f}, {&p.b, 0.7f}};
  const BlendLayer other[] = {{&p.a, 0.3f}, {&flipped, 0.7f}};
  const LocalPose x = blend(p.rest, one), y = blend(p.rest, other);
  for (size_t j = 0; j < 2; ++j) EXPECT_LT(degrees_between(x.rotations[j], y.rotations[j]), 1e-4) << j;
}

TEST(Blending, NormalisedLerpLagsSlerpAsTheHeaderSays) {
  // Rotations 90 degrees apart, a quarter of the way: 21.6 degrees, not 22.5.
  LocalPose rest = pose_of({{0, 0, 0}}, {glm::quat(1, 0, 0, 0)}, {{1, 1, 1}});
  LocalPose turned = pose_of({{0, 0, 0}}, {about_y(90)}, {{1, 1, 1}});
  const BlendLayer quarter[] = {{&rest, 0.75f}, {&turned, 0.25f}};
  EXPECT_NEAR(degrees_between(blend(rest, quarter).rotations[0], glm::quat(1, 0, 0, 0)), 21.60f, 0.01f);
}

TEST(Blending, BelowTheThresholdTheRestPoseFillsIn) {
  Poses p;
  const BlendLayer faint[] = {{&p.a, 0.05f}};
  const LocalPose out = blend(p.rest, faint);  // threshold 0.1: half a, half rest
  EXPECT_NEAR(out.translations[0].x, 0.5f, 1e-6);
  EXPECT_NEAR(out.translations[1].y, 1.5f, 1e-6);
  EXPECT_NEAR(degrees_between(out.rotations[1], glm::quat(1, 0, 0, 0)), 20.0f, 0.1f);
  const BlendLayer nothing[] = {{&p.a, 0.0f}};
  const LocalPose rest = blend(p.rest, nothing);
  EXPECT_EQ(rest.translations, p.rest.translations);
}

TEST(Blending, TheOutputMayBeALayer) {
  Poses p;
  const BlendLayer layers[] = {{&p.a, 0.25f}, {&p.b, 0.75f}};
  const LocalPose apart = blend(p.rest, layers);
  BlendingJob job;
  job.layers = layers;
  job.rest = &p.rest;
  job.output = &p.a;  // in place
  ASSERT_TRUE(job.Run());
  EXPECT_EQ(p.a.translations, apart.translations);
  EXPECT_EQ(p.a.scales, apart.scales);
}

TEST(Blending, RefusesWhatBreaksItsContract) {
  Poses p;
  const BlendLayer fine[] = {{&p.a, 0.5f}, {&p.b, 0.5f}};
  BlendingJob job;
  job.layers = fine;
  job.rest = &p.rest;
  job.output = &p.out;
  ASSERT_TRUE(job.Validate());
  LocalPose short_pose = pose_of({{0, 0, 0}}, {glm::quat(1, 0, 0, 0)}, {{1, 1, 1}});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const BlendLayer bad_weights[][1] = {{{&p.a, -0.5f}}, {{&p.a, nan}}, {{nullptr, 1.0f}}, {{&short_pose, 1.0f}}};
  for (const auto& layers : bad_weights) {
    BlendingJob bad = job;
    bad.layers = layers;
    EXPECT_FALSE(bad.Run());
  }
  BlendingJob none = job;
  none.layers = {};
  EXPECT_FALSE(none.Run());
  BlendingJob no_threshold = job;
  no_threshold.threshold = 0.0f;
  EXPECT_FALSE(no_threshold.Run());
  BlendingJob small_output = job;
  small_output.output = &short_pose;
  EXPECT_FALSE(small_output.Run());
  EXPECT_EQ(short_pose.translations.size(), 1u) << "nothing written";
}

}  // namespace
}  // namespace crowdprof

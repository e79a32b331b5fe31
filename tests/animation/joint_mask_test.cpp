// The joints a layer covers (lib/animation/joint_mask.h): the subtree of a
// named joint, easing in over the falloff, and a clear error for a name the
// skeleton lacks.
#include <gtest/gtest.h>

#include <vector>

#include "animation/joint_mask.h"

namespace crowdprof {
namespace {

// hips -> spine -> chest -> (neck -> head, arm -> hand); hips -> leg -> foot.
Skeleton small_body() {
  Skeleton s;
  s.names = {"hips", "spine", "chest", "neck", "head", "arm", "hand", "leg", "foot"};
  s.parents = {-1, 0, 1, 2, 3, 2, 5, 0, 7};
  return s;
}

TEST(JointMask, CoversTheSubtreeOfTheNamedJointOnly) {
  std::vector<float> w;
  ASSERT_EQ("", joint_mask(small_body(), "spine", 0, &w));
  EXPECT_EQ(w, (std::vector<float>{0, 1, 1, 1, 1, 1, 1, 0, 0}));
  ASSERT_EQ("", joint_mask(small_body(), "arm", 0, &w));
  EXPECT_EQ(w, (std::vector<float>{0, 0, 0, 0, 0, 1, 1, 0, 0}));
}

TEST(JointMask, EasesInOverTheFalloffDownTheChain) {
  std::vector<float> w;
  ASSERT_EQ("", joint_mask(small_body(), "spine", 2, &w));
  const float third = 1.0f / 3.0f, two_thirds = 2.0f / 3.0f;
  EXPECT_FLOAT_EQ(w[1], third);       // spine
  EXPECT_FLOAT_EQ(w[2], two_thirds);  // chest
  EXPECT_FLOAT_EQ(w[3], 1.0f);        // neck
  EXPECT_FLOAT_EQ(w[6], 1.0f);        // hand
  EXPECT_EQ(w[0], 0.0f);
  EXPECT_EQ(w[8], 0.0f);
}

TEST(JointMask, NoJointIsEveryJointAndAnUnknownOneIsNamedWithTheChoices) {
  std::vector<float> w;
  ASSERT_EQ("", joint_mask(small_body(), "", 0, &w));
  EXPECT_EQ(w, std::vector<float>(9, 1.0f));
  const std::string problem = joint_mask(small_body(), "Spine", 0, &w);
  EXPECT_NE(problem.find("no joint 'Spine'"), std::string::npos) << problem;
  EXPECT_NE(problem.find("hips, spine, chest"), std::string::npos) << problem;
  EXPECT_NE(joint_mask(small_body(), "spine", -1, &w), "");
}

}  // namespace
}  // namespace crowdprof

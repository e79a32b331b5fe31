// Local to model space in parent order (with glTF's parent offsets), and
// skinning matrices, against matrices worked out by hand.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "animation/local_pose.h"
#include "animation/pose.h"

namespace crowdprof {
namespace {

void expect_matrix(const glm::mat4& actual, const glm::mat4& expected) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(actual[c][r], expected[c][r], 1e-6f) << "column " << c << " row " << r;
}

// Columns as written on paper: x axis, y axis, z axis, origin.
glm::mat4 columns(glm::vec3 x, glm::vec3 y, glm::vec3 z, glm::vec3 origin) {
  return glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), glm::vec4(origin, 1));
}

glm::quat about(float degrees, glm::vec3 axis) {
  return glm::angleAxis(glm::radians(degrees), axis);
}

// A chain root -> child -> grandchild; the child sits under a non-joint node that
// moves it 3 along z (its parent offset).
Skeleton chain() {
  Skeleton s;
  s.names = {"root", "child", "grandchild"};
  s.parents = {-1, 0, 1};
  s.rest_translations = {glm::vec3(1, 0, 0), glm::vec3(0, 2, 0), glm::vec3(1, 0, 0)};
  s.rest_rotations = {about(90, {0, 0, 1}), glm::quat(1, 0, 0, 0), about(90, {1, 0, 0})};
  s.rest_scales = {glm::vec3(1), glm::vec3(2), glm::vec3(1)};
  s.parent_offsets = {glm::mat4(1), glm::translate(glm::mat4(1), glm::vec3(0, 0, 3)), glm::mat4(1)};
  s.inverse_binds.assign(3, glm::mat4(1));
  return s;
}

TEST(Pose, ResetToRestCopiesTheRestTransforms) {
  const Skeleton s = chain();
  LocalPose pose;
  pose.translations.assign(7, glm::vec3(9));
  reset_to_rest(s, &pose);
  ASSERT_EQ(pose.joint_count(), 3u);
  EXPECT_EQ(pose.translations, s.rest_translations);
  EXPECT_EQ(pose.rotations, s.rest_rotations);
  EXPECT_EQ(pose.scales, s.rest_scales);
}

TEST(Pose, LocalToModelOfAChainWithAParentOffset) {
  const Skeleton s = chain();
  LocalPose pose;
  reset_to_rest(s, &pose);
  std::vector<glm::mat4> model(3);
  ASSERT_TRUE((LocalToModelJob{&s, &pose, model}.Run()));

  // root: 90 degrees about z (x -> y, y -> -x), at (1, 0, 0).
  expect_matrix(model[0], columns({0, 1, 0}, {-1, 0, 0}, {0, 0, 1}, {1, 0, 0}));
  // child: root * offset T(0,0,3) * T(0,2,0) S(2): axes twice the root's; origin
  // root applied to (0, 2, 3) = (-2, 0, 3) + (1, 0, 0).
  expect_matrix(model[1], columns({0, 2, 0}, {-2, 0, 0}, {0, 0, 2}, {-1, 0, 3}));
  // grandchild: child * T(1,0,0) R_x(90) (y -> z, z -> -y): x axis = child's x
  // (0,2,0); y axis = child's z (0,0,2); z axis = -child's y (2,0,0); origin =
  // child applied to (1, 0, 0) = (0, 2, 0) + (-1, 0, 3).
  expect_matrix(model[2], columns({0, 2, 0}, {0, 0, 2}, {2, 0, 0}, {-1, 2, 3}));
}

TEST(Pose, RootParentOffsetAppliesBeforeTheRoot) {
  Skeleton s = chain();
  s.parent_offsets[0] = glm::translate(glm::mat4(1), glm::vec3(0, 5, 0));
  LocalPose pose;
  reset_to_rest(s, &pose);
  std::vector<glm::mat4> model(3);
  ASSERT_TRUE((LocalToModelJob{&s, &pose, model}.Run()));
  expect_matrix(model[0], columns({0, 1, 0}, {-1, 0, 0}, {0, 0, 1}, {1, 5, 0}));
  expect_matrix(model[2], columns({0, 2, 0}, {0, 0, 2}, {2, 0, 0}, {-1, 7, 3}));
}

TEST(Pose, OffsetsThatAreNotIdentityAreNotSkipped) {
  // Within a rounding error of the identity is still not the identity.
  Skeleton s = chain();
  s.parent_offsets[2][3][0] = 1e-3f;
  LocalPose pose;
  reset_to_rest(s, &pose);
  std::vector<glm::mat4> model(3);
  ASSERT_TRUE((LocalToModelJob{&s, &pose, model}.Run()));
  // The offset moves the grandchild 1e-3 along the child's x axis (0, 2, 0).
  EXPECT_NEAR(model[2][3][1], 2.0f + 2e-3f, 1e-6f);
}

TEST(Pose, SkinningMatricesAreModelTimesInverseBind) {
  Skeleton s = chain();
  LocalPose pose;
  reset_to_rest(s, &pose);
  std::vector<glm::mat4> model(3);
  ASSERT_TRUE((LocalToModelJob{&s, &pose, model}.Run()));
  // Bound in the rest pose: every skinning matrix of the rest pose is the identity.
  for (size_t j = 0; j < 3; ++j) s.inverse_binds[j] = glm::inverse(model[j]);
  std::vector<SkinMatrix> skin(3);
  ASSERT_TRUE((SkinningMatricesJob{&s, model, skin}.Run()));
  for (const SkinMatrix& m : skin) expect_matrix(m, glm::mat4(1));

  // And by hand: model T(1,2,3) after inverse bind T(-1,0,0) is T(0,2,3).
  std::vector<glm::mat4> moved(3, glm::translate(glm::mat4(1), glm::vec3(1, 2, 3)));
  s.inverse_binds.assign(3, glm::translate(glm::mat4(1), glm::vec3(-1, 0, 0)));
  ASSERT_TRUE((SkinningMatricesJob{&s, moved, skin}.Run()));
  expect_matrix(skin[1], columns({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 2, 3}));
}

TEST(Pose, JobsValidateTheirInput) {
  Skeleton s = chain();
  LocalPose pose;
  reset_to_rest(s, &pose);
  std::vector<glm::mat4> model(3), short_model(2);
  EXPECT_FALSE((LocalToModelJob{&s, &pose, short_model}.Run()));
  EXPECT_FALSE((LocalToModelJob{nullptr, &pose, model}.Run()));
  EXPECT_FALSE((LocalToModelJob{&s, nullptr, model}.Run()));
  LocalPose small = pose;
  small.scales.pop_back();
  EXPECT_FALSE((LocalToModelJob{&s, &small, model}.Run()));
  Skeleton cyclic = s;
  cyclic.parents[1] = 2;  // a child before its parent
  EXPECT_FALSE((LocalToModelJob{&cyclic, &pose, model}.Run()));
  Skeleton no_offsets = s;
  no_offsets.parent_offsets.clear();
  EXPECT_FALSE((LocalToModelJob{&no_offsets, &pose, model}.Run()));

  std::vector<SkinMatrix> skin(3), short_skin(2);
  EXPECT_FALSE((SkinningMatricesJob{&s, model, short_skin}.Run()));
  EXPECT_FALSE((SkinningMatricesJob{&s, short_model, skin}.Run()));
  EXPECT_FALSE((SkinningMatricesJob{nullptr, model, skin}.Run()));
  EXPECT_TRUE((SkinningMatricesJob{&s, model, skin}.Run()));
}

// Roots only, each under `offset` where `offset_every` divides its index.
Skeleton roots(size_t n, const glm::mat4& offset, size_t offset_every) {
  Skeleton s;
  for (size_t j = 0; j < n; ++j) {
    s.names.push_back("joint " + std::to_string(j));
    s.parents.push_back(-1);
    s.rest_translations.emplace_back(0.0f);
    s.rest_rotations.emplace_back(1.0f, 0.0f, 0.0f, 0.0f);
    s.rest_scales.emplace_back(1.0f);
    s.parent_offsets.push_back(j % offset_every == 0 ? offset : glm::mat4(1.0f));
    s.inverse_binds.emplace_back(1.0f);
  }
  return s;
}

// A pose for `s`: random translations up to `reach` along each axis, random
// unit rotations, scales from 0.25 to 3 (uneven).
LocalPose random_pose(const Skeleton& s, std::mt19937& rng, float reach) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), scale(0.25f, 3.0f);
  LocalPose pose;
  reset_to_rest(s, &pose);
  for (size_t j = 0; j < s.joint_count(); ++j) {
    pose.translations[j] = glm::vec3(unit(rng), unit(rng), unit(rng)) * reach;
    pose.rotations[j] = glm::normalize(glm::quat(unit(rng), unit(rng), unit(rng), unit(rng)));
    pose.scales[j] = glm::vec3(scale(rng), scale(rng), scale(rng));
  }
  return pose;
}

// The job turns rotations and scales into axes four joints at a time (one per
// lane): each joint's matrix is the same, bit for bit, as that joint's on its
// own, in every lane of a block and in a last block of 1 to 3, and it is the
// offset times its TRS.
TEST(Pose, EveryJointOfABlockOfFourIsTheSameAsOnItsOwn) {
  std::mt19937 rng(31);
  const glm::mat4 offset = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, -2.0f, 4.0f)) *
                           glm::mat4_cast(glm::normalize(glm::quat(0.9f, 0.1f, -0.3f, 0.2f)));
  for (size_t n = 1; n <= 9; ++n) {
    const Skeleton s = roots(n, offset, 3);
    const LocalPose pose = random_pose(s, rng, 10.0f);
    std::vector<glm::mat4> model(n);
    ASSERT_TRUE((LocalToModelJob{&s, &pose, model}.Run()));
    for (size_t j = 0; j < n; ++j) {
      const Skeleton one = roots(1, s.parent_offsets[j], 1);
      LocalPose alone;
      reset_to_rest(one, &alone);
      alone.translations[0] = pose.translations[j];
      alone.rotations[0] = pose.rotations[j];
      alone.scales[0] = pose.scales[j];
      std::vector<glm::mat4> own(1);
      ASSERT_TRUE((LocalToModelJob{&one, &alone, own}.Run()));
      EXPECT_EQ(0, std::memcmp(&model[j], &own[0], sizeof(glm::mat4))) << n << " joints, joint " << j;
      const glm::mat4 expected = s.parent_offsets[j] * glm::translate(glm::mat4(1.0f), pose.translations[j]) *
                                 glm::mat4_cast(pose.rotations[j]) * glm::scale(glm::mat4(1.0f), pose.scales[j]);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          EXPECT_NEAR(model[j][c][r], expected[c][r], 2e-5f)
              << n << " joints, joint " << j << " [" << c << "][" << r << "]";
    }
  }
}

// The job's arithmetic is glm's, bit for bit: glm::mat3_cast, each column times
// its scale, then the parent's columns times those axes and the translation in
// that order (tests build with -ffp-contract=off, as the library does). A chain
// of 11 joints, a branch among them, and offsets that are not the identity:
// joints in every lane, in a last block of 3, and parents in earlier blocks.
glm::mat4 reference_times_trs(const glm::mat4& p, const glm::vec3& t, const glm::quat& q, const glm::vec3& s) {
  const glm::mat3 rotation = glm::mat3_cast(q);
  glm::mat4 out;
  for (int c = 0; c < 3; ++c) {
    const glm::vec3 axis = rotation[c] * s[c];
    out[c] = p[0] * axis.x + p[1] * axis.y + p[2] * axis.z;
  }
  out[3] = p[0] * t.x + p[1] * t.y + p[2] * t.z + p[3];
  return out;
}

TEST(Pose, LocalToModelIsGlmsArithmeticBitForBit) {
  std::mt19937 rng(47);
  const size_t n = 11;
  Skeleton s = roots(n, glm::mat4(1.0f), 1);
  s.parents = {-1, 0, 1, 2, 3, 4, 2, 6, 7, 8, 9};
  const glm::mat4 offset = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.3f, -1.5f)) *
                           glm::mat4_cast(glm::normalize(glm::quat(0.8f, -0.2f, 0.4f, 0.1f)));
  for (size_t j : {0u, 5u, 9u}) s.parent_offsets[j] = offset;
  const LocalPose pose = random_pose(s, rng, 4.0f);
  std::vector<glm::mat4> model(n);
  ASSERT_TRUE((LocalToModelJob{&s, &pose, model}.Run()));
  std::vector<glm::mat4> expected(n);
  for (size_t j = 0; j < n; ++j) {
    const bool identity = s.parent_offsets[j] == glm::mat4(1.0f);
    const glm::vec3& t = pose.translations[j];
    const glm::quat& q = pose.rotations[j];
    const glm::vec3& sc = pose.scales[j];
    if (s.parents[j] < 0 && identity) {
      const glm::mat3 r = glm::mat3_cast(q);
      expected[j] = glm::mat4(glm::vec4(r[0] * sc.x, 0.0f), glm::vec4(r[1] * sc.y, 0.0f), glm::vec4(r[2] * sc.z, 0.0f),
                              glm::vec4(t, 1.0f));
    } else {
      glm::mat4 p = s.parents[j] < 0 ? glm::mat4(1.0f) : expected[static_cast<size_t>(s.parents[j])];
      p = s.parents[j] < 0 ? s.parent_offsets[j] : identity ? p : p * s.parent_offsets[j];
      expected[j] = reference_times_trs(p, t, q, sc);
    }
    EXPECT_EQ(0, std::memcmp(&model[j], &expected[j], sizeof(glm::mat4))) << "joint " << j;
  }
}

}  // namespace
}  // namespace crowdprof

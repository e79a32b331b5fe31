// Shadow cascades' cameras (issue 30's passes): the splits cover the crowd's
// depth in front of the camera, nearer cascades are thinner, and each
// cascade's orthographic box holds its slice of the view and every caster of
// the crowd between it and the light.
#include <gtest/gtest.h>

#include <array>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/shadow_cascades.h"

namespace crowdprof {
namespace {

Camera thesis_like_camera() {
  Camera camera;
  camera.eye = {0.0f, 6.0f, 30.0f};
  camera.target = {0.0f, 0.0f, 0.0f};
  camera.near_plane = 0.1f;
  camera.far_plane = 1000.0f;
  return camera;
}

const Aabb kCrowd{{-20.0f, 0.0f, -20.0f}, {20.0f, 2.0f, 20.0f}};

bool inside_clip(const glm::mat4& m, glm::vec3 p, float slack) {
  glm::vec4 c = m * glm::vec4(p, 1.0f);
  glm::vec3 ndc = glm::vec3(c) / c.w;
  return std::abs(ndc.x) <= 1 + slack && std::abs(ndc.y) <= 1 + slack && std::abs(ndc.z) <= 1 + slack;
}

TEST(ShadowCascades, SplitsSpanTheCrowdsDepthNearestThinnest) {
  Camera camera = thesis_like_camera();
  std::vector<float> splits = cascade_splits(camera, kCrowd, 4);
  ASSERT_EQ(splits.size(), 5u);
  // The crowd's box runs from about 10 to 50 units in front of the eye.
  EXPECT_GT(splits.front(), 8.0f);
  EXPECT_LT(splits.front(), 12.0f);
  EXPECT_GT(splits.back(), 48.0f);
  EXPECT_LT(splits.back(), 52.0f);
  for (size_t i = 1; i < splits.size(); ++i) EXPECT_GT(splits[i], splits[i - 1]);
  for (size_t i = 2; i < splits.size(); ++i)
    EXPECT_GT(splits[i] - splits[i - 1], splits[i - 1] - splits[i - 2]) << "cascade " << i - 1;
  EXPECT_EQ(cascade_splits(camera, kCrowd, 0).size(), 1u);
}

TEST(ShadowCascades, EachBoxHoldsItsSliceAndTheCastersTowardsTheLight) {
  Camera camera = thesis_like_camera();
  const size_t count = 3;
  std::vector<glm::mat4> cascades = shadow_cascades(camera, kCrowd, kLightDirection, count);
  ASSERT_EQ(cascades.size(), count);
  std::vector<float> splits = cascade_splits(camera, kCrowd, count);
  glm::mat4 view = camera.view();
  glm::mat4 to_world = glm::inverse(view);
  float half_h = std::tan(camera.fov_y() * 0.5f);
  for (size_t c = 0; c < count; ++c) {
    for (float depth : {splits[c], splits[c + 1]})
      for (float x : {-1.0f, 1.0f})
        for (float y : {-1.0f, 1.0f}) {
          glm::vec3 corner(to_world * glm::vec4(x * depth * half_h * camera.aspect, y * depth * half_h, -depth, 1.0f));
          EXPECT_TRUE(inside_clip(cascades[c], corner, 1e-3f)) << "cascade " << c << " misses a corner of its slice";
        }
    // A caster at the crowd's top, between the slice and the light, is drawn.
    glm::vec3 centre(to_world * glm::vec4(0.0f, 0.0f, -(splits[c] + splits[c + 1]) * 0.5f, 1.0f));
    glm::vec3 caster = centre + kLightDirection * 0.5f;
    if (caster.y <= kCrowd.max.y) {
      EXPECT_TRUE(inside_clip(cascades[c], caster, 1e-3f)) << "cascade " << c;
    }
  }
  // Nearer cascades see a smaller area: more shadow texels per metre.
  auto width = [](const glm::mat4& m) { return 2.0f / glm::length(glm::vec3(m[0][0], m[1][0], m[2][0])); };
  EXPECT_LT(width(cascades[0]), width(cascades[2]));
}

}  // namespace
}  // namespace crowdprof

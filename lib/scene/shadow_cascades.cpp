#include "scene/shadow_cascades.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace crowdprof {

namespace {

std::array<glm::vec3, 8> box_corners(const Aabb& box) {
  std::array<glm::vec3, 8> out;
  for (int c = 0; c < 8; ++c)
    out[static_cast<size_t>(c)] = {c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y,
                                   c & 4 ? box.max.z : box.min.z};
  return out;
}

// The camera frustum's corners at view depth `depth`, in world space.
std::array<glm::vec3, 4> corners_at(const Camera& camera, float depth) {
  glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  glm::vec3 up = glm::cross(right, forward);
  float half_h = depth * std::tan(camera.fov_y() * 0.5f), half_w = half_h * camera.aspect;
  glm::vec3 centre = camera.eye + forward * depth;
  return {centre - right * half_w - up * half_h, centre + right * half_w - up * half_h,
          centre - right * half_w + up * half_h, centre + right * half_w + up * half_h};
}

}  // namespace

std::vector<float> cascade_splits(const Camera& camera, const Aabb& crowd_box, size_t count) {
  glm::mat4 view = camera.view();
  float nearest = std::numeric_limits<float>::max(), farthest = 0.0f;
  for (const glm::vec3& corner : box_corners(crowd_box)) {
    float depth = -(view * glm::vec4(corner, 1.0f)).z;  // the camera looks down -z
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  float n = std::clamp(nearest, camera.near_plane, camera.far_plane);
  float f = std::clamp(farthest, n + camera.near_plane, camera.far_plane);
  std::vector<float> splits(count + 1);
  for (size_t i = 0; i <= count; ++i) {
    float t = count == 0 ? 0.0f : static_cast<float>(i) / static_cast<float>(count);
    splits[i] = 0.5f * n * std::pow(f / n, t) + 0.5f * (n + (f - n) * t);
  }
  return splits;
}

std::vector<glm::mat4> shadow_cascades(const Camera& camera, const Aabb& crowd_box, glm::vec3 light, size_t count) {
  std::vector<float> splits = cascade_splits(camera, crowd_box, count);
  light = glm::normalize(light);
  glm::vec3 up = std::abs(light.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  std::vector<glm::mat4> out;
  for (size_t c = 0; c < count; ++c) {
    std::array<glm::vec3, 8> slice;
    std::array<glm::vec3, 4> a = corners_at(camera, splits[c]), b = corners_at(camera, splits[c + 1]);
    std::copy(a.begin(), a.end(), slice.begin());
    std::copy(b.begin(), b.end(), slice.begin() + 4);
    glm::vec3 centre(0.0f);
    for (const glm::vec3& p : slice) centre += p / 8.0f;
    glm::mat4 light_view = glm::lookAt(centre + light, centre, up);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : slice) {
      glm::vec3 q(light_view * glm::vec4(p, 1.0f));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    // Casters between the slice and the light: as far towards it as the crowd goes.
    for (const glm::vec3& p : box_corners(crowd_box)) hi.z = std::max(hi.z, (light_view * glm::vec4(p, 1.0f)).z);
    // View space looks down -z: near and far are distances, -hi.z and -lo.z.
    out.push_back(glm::ortho(lo.x, hi.x, lo.y, hi.y, -hi.z, -lo.z) * light_view);
  }
  return out;
}

}  // namespace crowdprof

#include "scene/camera.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "base/errors.h"

namespace crowdprof {

glm::mat4 Camera::view() const {
  return glm::lookAt(eye, target, up);
}

float Lens::fov_x(float aspect) const {
  // Blender (BKE_camera_sensor_fit): the fitted side spans the sensor, the
  // other follows the aspect.
  bool horizontal = fit == SensorFit::Horizontal || (fit == SensorFit::Auto && aspect >= 1.0f);
  if (horizontal) return 2.0f * std::atan(0.5f * sensor_width_mm / focal_mm);
  float sensor = fit == SensorFit::Vertical ? sensor_height_mm : sensor_width_mm;
  return 2.0f * std::atan(0.5f * sensor / focal_mm * aspect);
}

float Lens::fov_y(float aspect) const {
  return 2.0f * std::atan(std::tan(0.5f * fov_x(aspect)) / aspect);
}

std::optional<SensorFit> parse_sensor_fit(std::string_view text) {
  if (text == "auto") return SensorFit::Auto;
  if (text == "horizontal") return SensorFit::Horizontal;
  if (text == "vertical") return SensorFit::Vertical;
  return std::nullopt;
}

std::string_view to_string(SensorFit fit) {
  switch (fit) {
    case SensorFit::Auto:
      return "auto";
    case SensorFit::Horizontal:
      return "horizontal";
    case SensorFit::Vertical:
      return "vertical";
  }
  return "?";
}

glm::mat4 Camera::projection() const {
  return glm::perspective(fov_y(), aspect, near_plane, far_plane);
}

Frustum frustum_of(const glm::mat4& m) {
  // Rows of the matrix (glm is column-major: m[column][row]).
  auto row = [&](int r) { return glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  Frustum f;
  f.planes = {row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1), row(3) + row(2), row(3) - row(2)};
  for (glm::vec4& p : f.planes) p /= glm::length(glm::vec3(p));
  return f;
}

bool intersects(const Frustum& frustum, const Aabb& box) {
  for (const glm::vec4& p : frustum.planes) {
    // The corner farthest along the plane's normal: if even it is outside, all are.
    glm::vec3 corner(p.x >= 0 ? box.max.x : box.min.x, p.y >= 0 ? box.max.y : box.min.y,
                     p.z >= 0 ? box.max.z : box.min.z);
    if (glm::dot(glm::vec3(p), corner) + p.w < 0.0f) return false;
  }
  return true;
}

Camera make_camera(const std::string& spec, const Aabb& crowd, float aspect, const Lens& lens) {
  Camera camera;
  camera.aspect = aspect;
  camera.lens = lens;
  glm::vec3 size = crowd.size();
  glm::vec3 center = crowd.center();
  float extent = std::max({size.x, size.z, 1e-3f});
  float height = std::max(size.y, 1e-3f);
  if (spec == "default") {
    // From the front (+Z) and above, near enough that the view's width at the
    // crowd's middle row covers about 70% of the crowd's: the corners of the
    // near rows fall outside the view, the far rows fit, as in the thesis scene.
    float tan_half_h = std::tan(0.5f * lens.fov_x(aspect));
    float distance = 0.35f * std::max(size.x, 1e-3f) / tan_half_h;
    float pitch = glm::radians(25.0f);
    camera.target = glm::vec3(center.x, crowd.min.y + 0.5f * height, center.z);
    camera.eye = camera.target + distance * glm::vec3(0.0f, std::sin(pitch), std::cos(pitch));
  } else if (spec == "all") {
    // From the front and above, far enough that the sphere around the crowd
    // fits inside the narrower of the two angles of view.
    float radius = 0.5f * std::max(glm::length(size), 1e-3f);
    float half = 0.5f * std::min(lens.fov_x(aspect), lens.fov_y(aspect));
    camera.target = center;
    camera.eye = center + radius / std::sin(half) * glm::normalize(glm::vec3(0.0f, 0.6f, 1.4f));
  } else if (spec == "close") {
    // Near the front row's centre and looking down on it, so that the rows
    // behind fall above the frame: a few copies fill the view.
    float pitch = glm::radians(45.0f);
    camera.target = glm::vec3(center.x, crowd.min.y + 0.4f * height, crowd.max.z - 0.3f * height);
    camera.eye = camera.target + 2.2f * height * glm::vec3(0.0f, std::sin(pitch), std::cos(pitch));
  } else {
    std::vector<float> values;
    const char* p = spec.data();
    const char* end = p + spec.size();
    while (p < end) {
      float v = 0;
      auto [next, ec] = std::from_chars(p, end, v);
      if (ec != std::errc() || !std::isfinite(v)) break;
      values.push_back(v);
      p = next;
      if (p < end && *p == ',')
        ++p;
      else
        break;
    }
    if (values.size() != 6 || p != end)
      throw SettingError("camera", spec, "expected default, all, close or EX,EY,EZ,TX,TY,TZ");
    camera.eye = glm::vec3(values[0], values[1], values[2]);
    camera.target = glm::vec3(values[3], values[4], values[5]);
    if (glm::length(camera.eye - camera.target) < 1e-6f)
      throw SettingError("camera", spec, "the eye and the target are the same point");
    // Looking straight down (or up) the world's up axis leaves lookAt no
    // sideways direction: the view would be NaN and the frame empty. Let the
    // top of the picture point down -Z (away from the default camera) instead.
    glm::vec3 forward = glm::normalize(camera.target - camera.eye);
    if (std::abs(glm::dot(forward, camera.up)) > 0.9999f) camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
  }
  float distance = glm::length(camera.eye - camera.target);
  camera.far_plane = std::max(1000.0f, 4.0f * (distance + extent));
  camera.near_plane = std::max(0.01f, distance * 1e-3f);
  return camera;
}

}  // namespace crowdprof

// The camera the crowd is culled (and later rendered) with.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "scene/bounds.h"

namespace crowdprof {

// Which side of the image the sensor spans, as Blender's camera says it.
enum class SensorFit : uint8_t {
  Auto,        // sensor_width spans the larger side (Blender's default)
  Horizontal,  // sensor_width spans the width
  Vertical,    // sensor_height spans the height
};

// A lens as Blender describes it: focal length and sensor, not an angle. The
// thesis scene was framed with Blender's default camera, 35 mm on a 32 mm
// sensor fitted to the larger side: 49.1 degrees across a 16:9 frame.
struct Lens {
  float focal_mm = 35.0f;
  float sensor_width_mm = 32.0f;
  float sensor_height_mm = 18.0f;  // only used with SensorFit::Vertical, as in Blender
  SensorFit fit = SensorFit::Auto;

  // Full angles, in radians, for a frame of `aspect` (width / height).
  float fov_x(float aspect) const;
  float fov_y(float aspect) const;
};

struct Camera {
  glm::vec3 eye{0.0f, 2.0f, 10.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  Lens lens;
  float aspect = 16.0f / 9.0f;  // the thesis's 1600x900 window
  float near_plane = 0.1f;
  float far_plane = 1000.0f;

  float fov_y() const { return lens.fov_y(aspect); }
  glm::mat4 view() const;
  glm::mat4 projection() const;
  glm::mat4 view_projection() const { return projection() * view(); }
};

// The six planes (a, b, c, d with ax + by + cz + d >= 0 inside) of a
// view-projection matrix (Gribb and Hartmann).
struct Frustum {
  std::array<glm::vec4, 6> planes;
};
Frustum frustum_of(const glm::mat4& view_projection);

// True when any part of the box may be inside (conservative: a box near a
// corner can pass although it is outside, never the other way).
bool intersects(const Frustum& frustum, const Aabb& box);

// Cameras by name, for a crowd whose copies lie inside `crowd_box`:
//   default  the thesis's framing: from the front and above, the near rows fill
//            the view and the crowd's far corners fall outside it;
//   all      back far enough to see every copy;
//   close    a few copies near the front centre.
// Or "EX,EY,EZ,TX,TY,TZ" for an eye and a target (up is +Y, or -Z when looking
// straight down or up). Throws UsageError.
Camera make_camera(const std::string& spec, const Aabb& crowd_box, float aspect, const Lens& lens = {});

// "auto", "horizontal", "vertical"; nullopt for anything else.
std::optional<SensorFit> parse_sensor_fit(std::string_view text);
std::string_view to_string(SensorFit fit);

}  // namespace crowdprof

#include "scene/screen_size.h"

#include <algorithm>
#include <cmath>

namespace crowdprof {

float screen_height_fraction(const glm::mat4& view_projection, const Aabb& box) {
  float low = 0.0f, high = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec4 p(corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                corner & 4 ? box.max.z : box.min.z, 1.0f);
    glm::vec4 clip = view_projection * p;
    if (clip.w <= 1e-6f) return 1.0f;
    float y = clip.y / clip.w;
    low = corner == 0 ? y : std::min(low, y);
    high = corner == 0 ? y : std::max(high, y);
  }
  return std::min(1.0f, 0.5f * (high - low));
}

uint8_t mesh_level_for(float fraction, uint8_t current, const float (&thresholds)[3], float hysteresis, size_t levels) {
  if (levels <= 1) return 0;
  const auto most = static_cast<uint8_t>(std::min<size_t>(levels - 1, 3));
  if (std::isnan(fraction)) return std::min(current, most);
  // Without hysteresis: one level per threshold the copy is below.
  uint8_t level = 0;
  while (level < most && fraction < thresholds[level]) ++level;
  // Finer than it was: only past the band above each threshold it crosses.
  while (level < std::min(current, most) && fraction < thresholds[level] * (1.0f + hysteresis)) ++level;
  return level;
}

}  // namespace crowdprof

#include "skinning/packed_vertex.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace crowdprof {

namespace {

// Round to nearest, ties to even, as the SIMD kernels' NearestInt does (the
// default rounding mode), for values well inside int32's range.
int32_t nearest(float x) {
  return static_cast<int32_t>(std::nearbyint(x));
}

}  // namespace

PositionQuantisation position_quantisation(glm::vec3 min, glm::vec3 max) {
  PositionQuantisation q;
  q.min = min;
  q.extent = max - min;
  for (int a = 0; a < 3; ++a) q.scale[a] = q.extent[a] > 0.0f ? kPositionCodeMax / q.extent[a] : 0.0f;
  return q;
}

glm::vec3 PositionQuantisation::max_error() const {
  const float eps = std::numeric_limits<float>::epsilon();
  glm::vec3 error;
  for (int a = 0; a < 3; ++a)
    error[a] = extent[a] / (2.0f * kPositionCodeMax) + 4.0f * eps * (std::abs(min[a]) + extent[a]);
  return error;
}

void quantise_position(const PositionQuantisation& q, glm::vec3 p, uint16_t out[3]) {
  for (int a = 0; a < 3; ++a) {
    // The kernels' order: subtract, multiply, clamp, round.
    const float code = std::clamp((p[a] - q.min[a]) * q.scale[a], 0.0f, kPositionCodeMax);
    out[a] = static_cast<uint16_t>(nearest(code));
  }
}

glm::vec3 dequantise_position(const PositionQuantisation& q, const uint16_t code[3]) {
  glm::vec3 p;
  for (int a = 0; a < 3; ++a) p[a] = q.min[a] + static_cast<float>(code[a]) / kPositionCodeMax * q.extent[a];
  return p;
}

uint32_t pack_normal(glm::vec3 n) {
  uint32_t word = 0;
  for (int a = 0; a < 3; ++a) {
    const int32_t code = nearest(std::clamp(n[a], -1.0f, 1.0f) * kNormalCodeMax);
    word |= (static_cast<uint32_t>(code) & 0x3ffu) << (10 * a);
  }
  return word;
}

glm::vec3 unpack_normal(uint32_t word) {
  glm::vec3 n;
  for (int a = 0; a < 3; ++a) {
    // Sign-extend the 10-bit field; GL maps -512 to -1 as it does -511.
    int32_t code = static_cast<int32_t>((word >> (10 * a)) & 0x3ffu);
    if (code >= 512) code -= 1024;
    n[a] = std::max(static_cast<float>(code) / kNormalCodeMax, -1.0f);
  }
  return n;
}

}  // namespace crowdprof

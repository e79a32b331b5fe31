// Slerp of two unit quaternions along the shorter arc, split in two: what
// depends only on the pair (the sign for the shorter arc, whether the keys are
// close enough for normalised lerp, the angle and 1/sin of it) and what depends
// on the fraction t (two sines). LINEAR rotation channels keep the first half
// per key segment (Channel::slerp, prepare_slerp) so that sampling pays only
// the second; both halves are the expressions slerp always used, so a prepared
// channel samples to the same bits as one worked out whole each time.
#pragma once

#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace crowdprof {

// Above this cosine (keys less than about 5.1 degrees apart) nlerp stays within
// 1.4e-6 of slerp; below it the exact slerp is worth its acos and sines.
inline constexpr float kNlerpAboveDot = 0.999f;

// The quaternion of 4 floats stored x, y, z, w (glTF's order).
inline glm::quat quat_from_xyzw(const float* p) {
  glm::quat q;
  q.x = p[0];
  q.y = p[1];
  q.z = p[2];
  q.w = p[3];
  return q;
}

struct SlerpSegment {
  float angle = 0.0f;     // between the keys on the shorter arc; 0 where nlerp
  float inv_sine = 0.0f;  // 1 / sin(angle); 0 where nlerp
  bool flip = false;      // the second key negated: q and -q are the same rotation
  bool nlerp = false;     // cosine above kNlerpAboveDot: normalised lerp instead
};

[[gnu::always_inline]] inline SlerpSegment slerp_segment(const glm::quat& a, const glm::quat& b) {
  SlerpSegment s;
  float cosine = glm::dot(a, b);
  if (cosine < 0.0f) {
    s.flip = true;
    cosine = -cosine;
  }
  if (cosine > kNlerpAboveDot) {
    s.nlerp = true;
    return s;
  }
  s.angle = std::acos(cosine);
  // sin^2 = (1 - c)(1 + c), not 1 - c*c: near c = 1 the subtraction 1 - c is
  // exact, while 1 - c*c cancels all but the rounding error of c*c. That form
  // was off by up to 3.0e-6 wherever the compiler did not fuse it into an FMA
  // (clang -O1, or GCC without -march=native) and 1.2e-6 where it did; this
  // one is within 1.3e-6 on GCC and clang, FMA or not (sampling_test).
  s.inv_sine = 1.0f / std::sqrt((1.0f - cosine) * (1.0f + cosine));
  return s;
}

// Slerp from `a` to `b` at fraction t, `s` being slerp_segment(a, b).
[[gnu::always_inline]] inline glm::quat slerp_along(const glm::quat& a, const glm::quat& b_in, const SlerpSegment& s,
                                                    float t) {
  const glm::quat b = s.flip ? -b_in : b_in;
  if (s.nlerp) return glm::normalize(a * (1.0f - t) + b * t);
  return a * (std::sin((1.0f - t) * s.angle) * s.inv_sine) + b * (std::sin(t * s.angle) * s.inv_sine);
}

}  // namespace crowdprof

#include "animation/sampling.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

namespace crowdprof {
namespace {

// Index k of the key segment [times[k], times[k+1]) holding t, for n >= 2 keys and
// times[0] < t < times[n-1]. `hint` is the segment found last time.
uint32_t find_segment(const float* times, uint32_t n, float t, uint32_t hint) {
  const uint32_t last = n - 2;
  uint32_t k = std::min(hint, last);
  if (t < times[k]) {
    // Backwards (a loop or a seek): the answer lies before the hint.
    return static_cast<uint32_t>(std::upper_bound(times, times + k, t) - times) - 1;
  }
  if (k == last || t < times[k + 1]) return k;  // same segment: the common case
  ++k;
  if (k == last || t < times[k + 1]) return k;  // the next one: keys slower than frames
  // A jump forward of more than one segment.
  return static_cast<uint32_t>(std::upper_bound(times + k + 1, times + last + 1, t) - times) - 1;
}

glm::vec3 vec3_at(const float* p) {
  return {p[0], p[1], p[2]};
}

glm::quat quat_at(const float* p) {
  return quat_from_xyzw(p);
}

// glTF's cubic Hermite spline between values v0 and v1 with out-tangent b0 and
// in-tangent a1, `span` seconds apart, at fraction s.
template <typename T>
T hermite(const T& v0, const T& b0, const T& v1, const T& a1, float span, float s) {
  const float s2 = s * s;
  const float s3 = s2 * s;
  const float h00 = 2.0f * s3 - 3.0f * s2 + 1.0f;
  const float h10 = (s3 - 2.0f * s2 + s) * span;
  const float h01 = -2.0f * s3 + 3.0f * s2;
  const float h11 = (s3 - s2) * span;
  return v0 * h00 + b0 * h10 + v1 * h01 + a1 * h11;
}

// Where a channel stands at one time: between keys k and k+1 at `alpha`, or
// holding key k (before the first key, after the last, or a single key).
struct Segment {
  uint32_t k = 0;
  float alpha = 0.0f;
  float span = 0.0f;
  bool hold = true;
};

Segment locate(const Channel& channel, float t, uint32_t* cursor_key) {
  const float* times = channel.times.data();
  const uint32_t n = static_cast<uint32_t>(channel.times.size());
  Segment s;
  if (n == 1 || t <= times[0]) {
    *cursor_key = 0;
    return s;
  }
  if (t >= times[n - 1]) {
    *cursor_key = n - 2;
    s.k = n - 1;
    return s;
  }
  s.k = find_segment(times, n, t, *cursor_key);
  *cursor_key = s.k;
  s.span = times[s.k + 1] - times[s.k];
  s.alpha = (t - times[s.k]) / s.span;
  s.hold = false;
  return s;
}

glm::vec3 sample_vec3(const Channel& channel, const Segment& s) {
  const float* v = channel.values.data();
  if (channel.interpolation == Interpolation::CubicSpline) {
    const float* key = v + 9 * s.k;  // in-tangent, value, out-tangent
    if (s.hold) return vec3_at(key + 3);
    return hermite(vec3_at(key + 3), vec3_at(key + 6), vec3_at(key + 12), vec3_at(key + 9), s.span, s.alpha);
  }
  const float* key = v + 3 * s.k;
  if (s.hold || channel.interpolation == Interpolation::Step) return vec3_at(key);
  return glm::mix(vec3_at(key), vec3_at(key + 3), s.alpha);
}

// slerp_shortest, inlined into the sampling loop: called, its quaternion came
// back in two registers, was stored in two halves and reloaded whole, which
// stalled on store forwarding once a rotation channel.
inline __attribute__((always_inline)) glm::quat slerp_shortest_inlined(const glm::quat& a, const glm::quat& b,
                                                                       float t) {
  return slerp_along(a, b, slerp_segment(a, b), t);
}

glm::quat sample_quat(const Channel& channel, const Segment& s) {
  const float* v = channel.values.data();
  if (channel.interpolation == Interpolation::CubicSpline) {
    const float* key = v + 12 * s.k;
    if (s.hold) return quat_at(key + 4);
    const glm::vec4 q = hermite(glm::make_vec4(key + 4), glm::make_vec4(key + 8), glm::make_vec4(key + 16),
                                glm::make_vec4(key + 12), s.span, s.alpha);
    const float length2 = glm::dot(q, q);
    // Tangents can cancel the values out; the nearer key is then the best guess.
    if (!(length2 > 1e-12f)) return quat_at(s.alpha < 0.5f ? key + 4 : key + 16);
    return quat_at(glm::value_ptr(q / std::sqrt(length2)));
  }
  const float* key = v + 4 * s.k;
  if (s.hold || channel.interpolation == Interpolation::Step) return quat_at(key);
  // Prepared (the loader's channels): the key pair's acos, square root and
  // divide were done once at load; only the two sines are left.
  if (!channel.slerp.empty()) return slerp_along(quat_at(key), quat_at(key + 4), channel.slerp[s.k], s.alpha);
  return slerp_shortest_inlined(quat_at(key), quat_at(key + 4), s.alpha);
}

// Floats a channel needs per key.
size_t floats_per_key(const Channel& channel) {
  const size_t groups = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
  return groups * static_cast<size_t>(channel.components());
}

}  // namespace

glm::quat slerp_shortest(const glm::quat& a, const glm::quat& b, float t) {
  return slerp_shortest_inlined(a, b, t);
}

void reset_cursor(const Action& action, SamplingCursor* cursor) {
  cursor->keys.assign(action.channels.size(), 0u);
}

bool SamplingJob::Validate() const {
  if (action == nullptr || cursor == nullptr || output == nullptr || !std::isfinite(time) ||
      !(action->start <= action->end))
    return false;
  const size_t channels = action->channels.size();
  if (targets.size() != channels || cursor->keys.size() != channels) return false;
  const size_t joints = output->translations.size();
  if (output->rotations.size() != joints || output->scales.size() != joints) return false;
  for (size_t i = 0; i < channels; ++i) {
    const Channel& channel = action->channels[i];
    if (targets[i] >= static_cast<int64_t>(joints)) return false;
    if (channel.times.empty() || channel.values.size() != channel.times.size() * floats_per_key(channel)) return false;
    if (!channel.slerp.empty() &&
        (channel.path != ChannelPath::Rotation || channel.interpolation != Interpolation::Linear ||
         channel.slerp.size() + 1 != channel.times.size()))
      return false;
  }
  return true;
}

bool SamplingJob::Run() const {
  if (!Validate()) return false;
  const float t = std::clamp(time, action->start, action->end);
  const size_t channels = action->channels.size();
  for (size_t i = 0; i < channels; ++i) {
    const int32_t joint = targets[i];
    if (joint < 0) continue;
    const Channel& channel = action->channels[i];
    const Segment s = locate(channel, t, &cursor->keys[i]);
    const auto j = static_cast<size_t>(joint);
    switch (channel.path) {
      case ChannelPath::Translation:
        output->translations[j] = sample_vec3(channel, s);
        break;
      case ChannelPath::Rotation:
        output->rotations[j] = sample_quat(channel, s);
        break;
      case ChannelPath::Scale:
        output->scales[j] = sample_vec3(channel, s);
        break;
    }
  }
  return true;
}

}  // namespace crowdprof

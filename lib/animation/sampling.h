// Sampling an action's channels at one time into a copy's local pose.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "animation/local_pose.h"
#include "asset/character.h"

namespace crowdprof {

// Per copy and per action: the key segment each channel was last sampled in.
// Playback moves forward a frame at a time, so the next segment is the same one
// or the one after, and finding it costs O(1) instead of a binary search. Time
// jumping backwards (a loop, a seek) falls back to a binary search.
struct SamplingCursor {
  std::vector<uint32_t> keys;  // one per channel of the action
};

// Sizes `cursor` for `action` and rewinds it to the first keys.
void reset_cursor(const Action& action, SamplingCursor* cursor);

// Writes the value of every bound channel of `action` at `time` into `output`.
// Joints without a bound channel keep what `output` already held, so reset it to
// rest first when the action leaves joints unanimated.
// Interpolation follows glTF 2.0: STEP holds a key's value; LINEAR lerps
// translations and scales and slerps rotations on the shorter arc; CUBICSPLINE
// is the Hermite spline of the spec's appendix, tangents scaled by the key
// interval, rotations normalised after. Before a channel's first key its first
// value holds, after its last key its last value.
struct SamplingJob {
  const Action* action = nullptr;
  // Seconds on the action's own clock; clamped to [action->start, action->end].
  float time = 0.0f;
  // Joint written by each channel, -1 to skip it (see binding.h).
  std::span<const int32_t> targets;
  SamplingCursor* cursor = nullptr;  // reset_cursor(*action, ...) before first use
  LocalPose* output = nullptr;

  // Pointers set, time finite, one target and one cursor key per channel, every
  // target inside `output`, every channel's arrays sized for its key count.
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// Spherical linear interpolation of unit quaternions along the shorter arc.
// Keys closer than about 5 degrees apart use normalised lerp instead, which
// differs from the exact slerp by less than 2e-6 there (sampling_test checks).
glm::quat slerp_shortest(const glm::quat& a, const glm::quat& b, float t);

}  // namespace crowdprof

// Baked animation (mode `baked`): at load, every action is sampled at a fixed
// rate into a table of skinning matrices, so that per frame a copy needs only
// its action and time, and the GPU interpolates between two baked samples (as
// crowd renderers with animation textures do). This is animation code: it
// knows nothing of GL; lib/render uploads what it makes.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "animation/local_pose.h"
#include "animation/sampling.h"
#include "animation/skin_matrix.h"
#include "asset/character.h"

namespace crowdprof {

// The rate `baked` samples actions at unless told otherwise (--bake-rate).
inline constexpr float kDefaultBakeRateHz = 30.0f;

// An action baked at `rate_hz` is cut into max(1, ceil(duration x rate)) equal
// intervals over [start, end]; the samples are their ends, first and last key
// included, so a looping copy never interpolates across the loop. The interval
// is duration / intervals <= 1 / rate.
size_t baked_intervals(const Action& action, float rate_hz);
inline size_t baked_samples(const Action& action, float rate_hz) {
  return baked_intervals(action, rate_hz) + 1;
}

// Where a time on the action's clock falls among the samples: sample index u in
// [0, intervals] with its fraction (u = 2.25: a quarter of the way from sample 2
// to sample 3). Times outside [start, end] are clamped.
float baked_position(const Action& action, size_t intervals, float time);

// Samples one action: output[s x joints + j] is joint j's skinning matrix at
// sample s (sample-major, so one sample's palette is contiguous).
struct BakeJob {
  const Skeleton* skeleton = nullptr;
  const Action* action = nullptr;
  std::span<const int32_t> targets;  // joint of each channel (binding.h)
  float rate_hz = kDefaultBakeRateHz;
  // Scratch, sized by the caller: a cursor (reset_cursor), a pose and one
  // model matrix per joint.
  SamplingCursor* cursor = nullptr;
  LocalPose* pose = nullptr;
  std::span<glm::mat4> model;
  std::span<SkinMatrix> output;  // baked_samples(*action, rate_hz) x joints

  // Pointers set, rate finite and > 0, spans sized as above, a target per channel.
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// What the vertex shader of `baked` computes: the palette at sample position
// u, each matrix linearly interpolated between the two samples around it.
// `baked` holds samples x joints matrices as BakeJob writes them.
struct BakedPaletteJob {
  std::span<const SkinMatrix> baked;
  size_t joints = 0;
  float position = 0.0f;         // from baked_position
  std::span<SkinMatrix> output;  // one per joint

  // At least two samples of `joints` matrices, position finite, output sized.
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// What baked.vert computes for a copy fading from one action into another
// (issue 53): each action's palette as BakedPaletteJob makes it, mixed matrix
// by matrix, `from_weight` of the action left. Mixing the matrices puts each
// vertex where mixing the two skinned vertices would (skinning is linear in
// them); it differs from the exact fade, which mixes the local poses.
struct BakedFadeJob {
  BakedPaletteJob now;   // its output is the job's
  BakedPaletteJob from;  // its output: scratch of one matrix per joint
  float from_weight = 0.0f;

  // Both jobs valid over the same joints, distinct outputs, weight in [0, 1].
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

}  // namespace crowdprof

namespace crowdprof {

// Every action of a character baked, one after another: action a's samples
// start at matrix first_sample[a] x joints. Made once at load.
struct BakedCharacter {
  float rate_hz = kDefaultBakeRateHz;
  size_t joints = 0;
  std::vector<size_t> first_sample, intervals;  // per action
  std::vector<SkinMatrix> matrices;             // every action's samples x joints
  size_t samples() const { return joints ? matrices.size() / joints : 0; }
  std::span<const SkinMatrix> action(size_t a) const {
    return std::span(matrices).subspan(first_sample[a] * joints, (intervals[a] + 1) * joints);
  }
};

// Runs BakeJob over every action of `character`, `targets[a]` being action
// a's bindings. Allocates the result and its scratch (a load-time step, not a
// job). False when a BakeJob refuses its input.
bool bake_character(const Character& character, std::span<const std::span<const int32_t>> targets, float rate_hz,
                    BakedCharacter* out);

}  // namespace crowdprof

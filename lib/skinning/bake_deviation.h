// How far mode `baked` puts vertices from where exact sampling puts them: the
// baked matrices are interpolated linearly between samples, which cuts the
// corners of rotations (a vertex at distance r from a joint turning by angle a
// per interval lands up to r (1 - cos(a / 2)) inside its arc).
#pragma once

#include <cstddef>
#include <span>

#include "animation/bake.h"
#include "animation/sampling.h"
#include "skinning/skinning_plan.h"

namespace crowdprof {

// Probes per baked interval, at 1/4, 1/2 and 3/4 of it: linear interpolation
// is exact at the samples and strays most between them.
inline constexpr int kDeviationProbes = 3;

// The largest distance, in model units, between a vertex skinned with the
// exact pose and the same vertex skinned with the baked palette, over every
// vertex and every probe of one action (*max_deviation is raised, never lowered,
// so one variable collects several actions).
struct BakeDeviationJob {
  const Skeleton* skeleton = nullptr;
  const Action* action = nullptr;
  std::span<const int32_t> targets;   // joint of each channel
  std::span<const SkinMatrix> baked;  // the action's samples, as BakeJob wrote them
  size_t intervals = 0;               // baked_intervals(action, rate)
  const SkinningPlan* plan = nullptr;
  // Scratch, sized by the caller: cursor (reset_cursor), pose, one matrix per
  // joint in model, exact and interpolated, one vertex of the plan per element of
  // the three vertex spans.
  SamplingCursor* cursor = nullptr;
  LocalPose* pose = nullptr;
  std::span<glm::mat4> model;
  std::span<SkinMatrix> exact, interpolated;
  std::span<glm::vec3> exact_positions, baked_positions, normals;
  float* max_deviation = nullptr;

  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// The whole character: its largest deviation over every action, and its
// height as it stands (asset/standing.h) to express it as a fraction. Allocates its scratch (a load-time step).
struct BakeDeviation {
  float model_units = 0.0f;
  float height = 0.0f;
  float fraction_of_height() const { return height > 0.0f ? model_units / height : 0.0f; }
};
BakeDeviation measure_bake_deviation(const Character& character, std::span<const std::span<const int32_t>> targets,
                                     const BakedCharacter& baked, const SkinningPlan& plan);

}  // namespace crowdprof

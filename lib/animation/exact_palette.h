// One copy's skinning matrices at an exact time, sampled from nothing an
// earlier frame left (the rest pose, a fresh cursor): the reference the
// end-of-run checks (fidelity, drawn error, culling audit) measure what was
// drawn against.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "animation/local_pose.h"
#include "animation/sampling.h"
#include "animation/skin_matrix.h"
#include "asset/character.h"

namespace crowdprof {

// Scratch grown on first use and reused by later calls: one per thread.
struct ExactPalette {
  LocalPose pose;
  SamplingCursor cursor;
  std::vector<glm::mat4> model;
  std::vector<SkinMatrix> palette;

  // `action` sampled at `time` through `targets` (binding.h), or the rest pose
  // when `action` is null; one matrix per joint, valid until the next call.
  std::span<const SkinMatrix> at(const Skeleton& skeleton, const Action* action, std::span<const int32_t> targets,
                                 float time);
};

}  // namespace crowdprof

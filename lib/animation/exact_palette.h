// One copy's skinning matrices at an exact time, sampled from nothing an
// earlier frame left (the rest pose, a fresh cursor): the reference the
// end-of-run checks (fidelity, drawn error, culling audit) measure what was
// drawn against.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "animation/layering.h"
#include "animation/local_pose.h"
#include "animation/sampling.h"
#include "animation/skin_matrix.h"
#include "asset/character.h"

namespace crowdprof {

// Scratch grown on first use and reused by later calls: one per thread.
// A character's layers and what their actions need (--anim-layer), for the
// calls below; null: none.
struct ExactLayers {
  const CharacterLayers* layers = nullptr;
  std::span<const Action> actions;           // the character's
  std::span<const ActionBindings> bindings;  // per action
  const LocalPose* rest = nullptr;
};

struct ExactPalette {
  LocalPose pose, from_pose, layered;
  std::vector<LocalPose> layer_poses, deltas;
  SamplingCursor cursor;
  std::vector<glm::mat4> model;
  std::vector<SkinMatrix> palette;

  // `action` sampled at `time` through `targets` (binding.h), or the rest pose
  // when `action` is null; one matrix per joint, valid until the next call.
  // With `layers`, the action's pose with them laid over it.
  std::span<const SkinMatrix> at(const Skeleton& skeleton, const Action* action, std::span<const int32_t> targets,
                                 float time, const ExactLayers& layers = {});
  // A copy fading (issue 53): `from` at `from_time` and `action` at `time`,
  // each sampled from rest, blended with `weight` of `action`
  // (animation/blending.h, over `rest`).
  std::span<const SkinMatrix> fading(const Skeleton& skeleton, const LocalPose& rest, const Action& from,
                                     std::span<const int32_t> from_targets, float from_time, const Action& action,
                                     std::span<const int32_t> targets, float time, float weight,
                                     const ExactLayers& layers = {});

 private:
  // The layers over `own` (one pose or a fade's two) into `layered`, the own
  // action at `time` giving the layers' times; `own`'s poses unless no layers.
  const LocalPose* lay(const Skeleton& skeleton, std::span<const BlendLayer> own, const Action& action, float time,
                       const ExactLayers& layers);
};

}  // namespace crowdprof

// Blending several local poses of one skeleton into one (a crossfade between
// two actions, issue 53; layers, issue 56), in ozz-animation's BlendingJob's
// terms: each layer a pose and a weight, the rest pose filling in below a
// threshold of total weight.
#pragma once

#include <span>

#include "animation/local_pose.h"

namespace crowdprof {

// One pose of a blend and how much of it to take.
struct BlendLayer {
  BlendLayer() = default;
  BlendLayer(const LocalPose* p, float w, std::span<const float> mask = {}) : pose(p), weight(w), joint_weights(mask) {}

  const LocalPose* pose = nullptr;
  float weight = 0.0f;  // >= 0; 0 leaves the layer out
  // A mask: the share of `weight` each joint takes, one value per joint of the
  // skeleton (empty: 1 everywhere). A joint whose share is 0 (or negative, or
  // NaN) is left out of this layer as a weight 0 layer is, so the other layers
  // give it the same bits as without this one.
  std::span<const float> joint_weights;
};

// Per joint: translations and scales are the layers' weighted mean; rotations
// the normalised weighted sum of their quaternions, each turned onto the
// hemisphere of the sum so far (normalised lerp on the shortest arc). Where the
// weights add up to less than `threshold`, the rest pose is added with what is
// missing, so a blend of nearly nothing tends to rest instead of dividing by
// almost zero (ozz's rule). A layer of weight 1 alone gives its pose back (its
// rotations renormalised: within 1e-7); weight 0 layers are skipped, not
// special-cased.
//
// Why normalised lerp and not slerp (which the BGE uses for its two-pose
// blend): it is what ozz and Unreal blend with, it takes any number of layers
// in any order (slerp is defined for two), and costs a multiply-add per
// component. Between two poses it is exact at weights 0, 1/2 and 1 and moves
// non-uniformly in between: for rotations 90 degrees apart the angle reached at
// weight 1/4 is 21.6 degrees against slerp's 22.5, less apart for closer ones,
// and a crossfade's poses are close (the same skeleton, the same moment of
// motion).
//
// Four joints at a time in SIMD (blending_kernels.h, on the target --simd
// chooses), the last joint count % 4 one by one; the same operations in the
// same order either way and no fused multiply-add, so every target gives the
// same bits: a digest with transitions does not depend on the blend's target.
// Weights 0 and 1 are not special cases: 0 skips the layer, 1 divides by 1.
//
// Masks (a layer's joint_weights) make the weights, their sum and the rest
// pose's share per joint, in the same operations and order, so a mask of all
// ones gives the bits of no mask. To lay an action over the upper body only,
// give it the mask m and the layers below it the mask 1 - m: where m is 1 the
// action replaces them, where it is 0 they are untouched.
//
// Additive layers come after the blend, in order: each is a delta from a
// reference pose (additive_delta below), added with its weight (and mask) as
// ozz's additive layers are: translation += w * delta; rotation *= the delta
// rotation taken a w of the way from identity (normalised lerp, on the
// hemisphere of identity); scale *= 1 + w * (delta - 1). A delta of identity
// changes nothing. Additive layers are blended one joint at a time.
struct BlendingJob {
  std::span<const BlendLayer> layers;
  const LocalPose* rest = nullptr;                   // reset_to_rest's pose of the same skeleton
  float threshold = 0.1f;                            // > 0
  LocalPose* output = nullptr;                       // sized like `rest`; may be one of the layers' poses
  std::span<const BlendLayer> additive_layers = {};  // deltas; none may be `output`

  // Rest and output set and sized alike, threshold finite and > 0, at least one
  // layer, each (additive ones too) with a pose sized like rest, a finite weight
  // >= 0, and no mask or a mask of one value per joint; no additive layer's pose
  // is the output.
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// The delta that an additive layer adds: `pose` relative to `reference` (an
// action's first frame, as glTF exporters and ozz's additive builder take it):
// translation - reference's, conjugate(reference's rotation) * rotation, scale /
// reference's. `delta` is sized like `pose` (allocating when it grows).
void additive_delta(const LocalPose& pose, const LocalPose& reference, LocalPose* delta);

}  // namespace crowdprof

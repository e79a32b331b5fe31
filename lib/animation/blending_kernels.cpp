// Compiled once per SIMD target by Highway's foreach_target (this file includes
// itself for each target in HWY_TARGETS); HWY_DYNAMIC_DISPATCH calls the one
// simd_target.h chose.
#include "animation/blending_kernels.h"

#include <cstddef>
#include <vector>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "animation/blending_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace crowdprof {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Four joints a vector (ozz's SoA width).
using BlendTag = hn::CappedTag<float, 4>;
using BlendVec = hn::Vec<BlendTag>;

// One group's running sums. Translations and scales stay as stored (x y z of
// joint 0, then joint 1, ...: three vectors), as a weighted sum is the same
// per component; rotations are split into x, y, z and w, one joint a lane,
// for the per-joint dot products.
struct BlendSums {
  BlendVec translation[3], scale[3], rotation[4];
};

// The poses' arrays read as floats: x y z a vec3, x y z w a quaternion (glm's
// order unless GLM_FORCE_QUAT_DATA_WXYZ).
static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::quat) == 16 && offsetof(glm::quat, x) == 0 &&
              offsetof(glm::quat, w) == 12);
const float* floats_of(const std::vector<glm::vec3>& v) {
  return &v[0].x;
}
const float* floats_of(const std::vector<glm::quat>& v) {
  return &v[0].x;
}
float* floats_of(std::vector<glm::vec3>& v) {
  return &v[0].x;
}
float* floats_of(std::vector<glm::quat>& v) {
  return &v[0].x;
}

// w1*w2 + x1*x2 + y1*y2 + z1*z2 in glm::dot's order for quaternions:
// (w + x) + (y + z).
HWY_INLINE BlendVec QuatDot(const BlendVec (&a)[4], const BlendVec (&b)[4]) {
  return hn::Add(hn::Add(hn::Mul(a[3], b[3]), hn::Mul(a[0], b[0])), hn::Add(hn::Mul(a[1], b[1]), hn::Mul(a[2], b[2])));
}

// sums += weight * pose, each rotation first turned onto the hemisphere of the
// sum so far (the scalar loop's `dot < 0 ? -weight * q : weight * q`).
HWY_INLINE void AddWeighted(BlendTag d, const LocalPose& pose, float weight, size_t first, BlendSums& sums) {
  const size_t lanes = hn::Lanes(d);
  const BlendVec w = hn::Set(d, weight);
  const float* t = floats_of(pose.translations) + 3 * first;
  const float* s = floats_of(pose.scales) + 3 * first;
  for (size_t k = 0; k < 3; ++k) {
    sums.translation[k] = hn::Add(sums.translation[k], hn::Mul(w, hn::LoadU(d, t + k * lanes)));
    sums.scale[k] = hn::Add(sums.scale[k], hn::Mul(w, hn::LoadU(d, s + k * lanes)));
  }
  BlendVec q[4];
  hn::LoadInterleaved4(d, floats_of(pose.rotations) + 4 * first, q[0], q[1], q[2], q[3]);
  const BlendVec signed_w = hn::IfThenElse(hn::Lt(QuatDot(sums.rotation, q), hn::Zero(d)), hn::Neg(w), w);
  for (size_t c = 0; c < 4; ++c) sums.rotation[c] = hn::Add(sums.rotation[c], hn::Mul(signed_w, q[c]));
}

// The rotations' sums, each divided by its length, stored x y z w.
HWY_INLINE void StoreNormalised(BlendTag d, const BlendVec (&rotation)[4], float* to) {
  const BlendVec norm = hn::Div(hn::Set(d, 1.0f), hn::Sqrt(QuatDot(rotation, rotation)));
  hn::StoreInterleaved4(hn::Mul(rotation[0], norm), hn::Mul(rotation[1], norm), hn::Mul(rotation[2], norm),
                        hn::Mul(rotation[3], norm), d, to);
}

size_t BlendJointGroups(const BlendKernelArgs& args) {
#if HWY_TARGET == HWY_SCALAR
  // One lane is the scalar loop with more steps, so slower than it: leave
  // every joint to it.
  (void)args;
  return 0;
#endif
  const BlendTag d;
  const size_t lanes = hn::Lanes(d);
  const size_t joints = args.rest->joint_count();
  const size_t end = joints - joints % lanes;
  const BlendVec inverse = hn::Set(d, args.inverse_total);
  LocalPose& out = *args.output;
  // Group by group, every input read before the output is written: the output
  // may be one of the layers.
  for (size_t first = 0; first < end; first += lanes) {
    BlendSums sums;
    for (size_t k = 0; k < 3; ++k) sums.translation[k] = sums.scale[k] = hn::Zero(d);
    for (BlendVec& c : sums.rotation) c = hn::Zero(d);
    for (const BlendLayer& layer : args.layers)
      if (layer.weight > 0.0f) AddWeighted(d, *layer.pose, layer.weight, first, sums);
    if (args.fill_rest) AddWeighted(d, *args.rest, args.rest_weight, first, sums);
    float* t = floats_of(out.translations) + 3 * first;
    float* s = floats_of(out.scales) + 3 * first;
    for (size_t k = 0; k < 3; ++k) {
      hn::StoreU(hn::Mul(sums.translation[k], inverse), d, t + k * lanes);
      hn::StoreU(hn::Mul(sums.scale[k], inverse), d, s + k * lanes);
    }
    StoreNormalised(d, sums.rotation, floats_of(out.rotations) + 4 * first);
  }
  return end;
}

// The masked kernel's sums: one joint a lane for every component, so that a
// joint's weight is one lane's.
struct MaskedSums {
  BlendVec translation[3], scale[3], rotation[4], total;
};

// sums += weight * pose in the lanes whose weight is > 0; the others are left
// as they were (the scalar loop skips those joints), so a joint outside every
// mask but one gets the bits of that one alone. A mask's joints are
// contiguous (parents first, subtrees together), so most groups lie wholly
// outside a layer (skipped) or wholly inside it (no selects).
HWY_INLINE void AddMasked(BlendTag d, const LocalPose& pose, BlendVec w, size_t first, MaskedSums& sums) {
  const auto on = hn::Gt(w, hn::Zero(d));
  if (hn::AllFalse(d, on)) return;
  const bool all = hn::AllTrue(d, on);
  auto pick = [&](BlendVec added, BlendVec old) { return all ? added : hn::IfThenElse(on, added, old); };
  BlendVec t[3], s[3], q[4];
  hn::LoadInterleaved3(d, floats_of(pose.translations) + 3 * first, t[0], t[1], t[2]);
  hn::LoadInterleaved3(d, floats_of(pose.scales) + 3 * first, s[0], s[1], s[2]);
  hn::LoadInterleaved4(d, floats_of(pose.rotations) + 4 * first, q[0], q[1], q[2], q[3]);
  for (size_t k = 0; k < 3; ++k) {
    sums.translation[k] = pick(hn::Add(sums.translation[k], hn::Mul(w, t[k])), sums.translation[k]);
    sums.scale[k] = pick(hn::Add(sums.scale[k], hn::Mul(w, s[k])), sums.scale[k]);
  }
  const BlendVec signed_w = hn::IfThenElse(hn::Lt(QuatDot(sums.rotation, q), hn::Zero(d)), hn::Neg(w), w);
  for (size_t c = 0; c < 4; ++c)
    sums.rotation[c] = pick(hn::Add(sums.rotation[c], hn::Mul(signed_w, q[c])), sums.rotation[c]);
  sums.total = pick(hn::Add(sums.total, w), sums.total);
}

size_t BlendMaskedJointGroups(const BlendKernelArgs& args) {
#if HWY_TARGET == HWY_SCALAR
  (void)args;
  return 0;
#endif
  const BlendTag d;
  const size_t lanes = hn::Lanes(d);
  const size_t joints = args.rest->joint_count();
  const size_t end = joints - joints % lanes;
  const BlendVec one = hn::Set(d, 1.0f);
  const BlendVec threshold = hn::Set(d, args.threshold);
  LocalPose& out = *args.output;
  for (size_t first = 0; first < end; first += lanes) {
    MaskedSums sums;
    for (size_t k = 0; k < 3; ++k) sums.translation[k] = sums.scale[k] = hn::Zero(d);
    for (BlendVec& c : sums.rotation) c = hn::Zero(d);
    sums.total = hn::Zero(d);
    for (const BlendLayer& layer : args.layers) {
      if (!(layer.weight > 0.0f)) continue;
      const BlendVec w = hn::Set(d, layer.weight);
      AddMasked(d, *layer.pose, layer.joint_weights.empty() ? w : hn::Mul(w, hn::LoadU(d, &layer.joint_weights[first])),
                first, sums);
    }
    // Below the threshold the rest pose fills in what is missing (lanes at or
    // over it get a weight of 0, which AddMasked leaves out).
    const BlendVec short_of = hn::Sub(threshold, sums.total);
    AddMasked(d, *args.rest, hn::IfThenElseZero(hn::Lt(sums.total, threshold), short_of), first, sums);
    const BlendVec inverse = hn::Div(one, sums.total);
    BlendVec t[3], s[3];
    for (size_t k = 0; k < 3; ++k) {
      t[k] = hn::Mul(sums.translation[k], inverse);
      s[k] = hn::Mul(sums.scale[k], inverse);
    }
    hn::StoreInterleaved3(t[0], t[1], t[2], d, floats_of(out.translations) + 3 * first);
    hn::StoreInterleaved3(s[0], s[1], s[2], d, floats_of(out.scales) + 3 * first);
    StoreNormalised(d, sums.rotation, floats_of(out.rotations) + 4 * first);
  }
  return end;
}

}  // namespace HWY_NAMESPACE
}  // namespace crowdprof
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace crowdprof {

HWY_EXPORT(BlendJointGroups);
HWY_EXPORT(BlendMaskedJointGroups);

size_t blend_joint_groups(const BlendKernelArgs& args) {
  return HWY_DYNAMIC_DISPATCH(BlendJointGroups)(args);
}

size_t blend_masked_joint_groups(const BlendKernelArgs& args) {
  return HWY_DYNAMIC_DISPATCH(BlendMaskedJointGroups)(args);
}

}  // namespace crowdprof
#endif

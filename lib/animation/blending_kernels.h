// The SIMD body of BlendingJob (blending.h), compiled once per target by
// Highway and picked at run time as the skinning kernels are (simd_target.h:
// --simd and CROWDPROF_SIMD choose for both).
#pragma once

#include <cstddef>
#include <span>

#include "animation/blending.h"

namespace crowdprof {

// A checked job's inputs, its weights already summed (BlendingJob::Run).
struct BlendKernelArgs {
  std::span<const BlendLayer> layers;  // weight 0 layers are skipped
  const LocalPose* rest = nullptr;
  bool fill_rest = false;  // the layers' weights add up to less than the threshold
  float rest_weight = 0.0f;
  float inverse_total = 0.0f;  // 1 / (layers' weights + rest_weight)
  LocalPose* output = nullptr;
  float threshold = 0.1f;  // the masked kernel's, per joint
};

// Blends joints [0, returned count): whole groups of four joints (none on
// Highway's SCALAR target, where one lane is slower than the caller's loop);
// the caller blends the rest. Per joint the same
// operations in the same order as the scalar loop, no fused multiply-add, so
// the same bits on every target.
size_t blend_joint_groups(const BlendKernelArgs& args);

// The same where some layer has a mask: weights, their sums and the rest
// pose's share per joint (fill_rest, rest_weight and inverse_total unused),
// as the scalar loop makes them.
size_t blend_masked_joint_groups(const BlendKernelArgs& args);

}  // namespace crowdprof

// Which SIMD target the skinning kernels and the blend job (animation/
// blending_kernels.h) run on. They are compiled for every
// x86-64 target in the Highway's HWY_TARGETS (with Debian 12's Highway 1.0.3:
// SCALAR, the baseline x86-64 with SSE2, then SSSE3, SSE4, AVX2 and AVX3 =
// AVX-512) and the best one the CPU supports is used, unless a lower one is
// forced.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace crowdprof {

// Highway's name of the target skinning runs on now, e.g. "AVX2".
std::string active_simd_target();

// The targets compiled in that this CPU can run, best first.
std::vector<std::string> available_simd_targets();

// Every target compiled in, best first, whether this CPU can run it or not.
std::vector<std::string> compiled_simd_targets();

// Runs skinning on `name` (case-insensitive, one of available_simd_targets())
// from now on; "" goes back to the best. Returns "" or, changing nothing, why
// not (unknown target, or one this CPU or build cannot run).
std::string force_simd_target(std::string_view name);

// The environment variable that forces a target as --simd does.
constexpr const char* kSimdEnvironmentVariable = "CROWDPROF_SIMD";

}  // namespace crowdprof

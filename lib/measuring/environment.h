// What a result was measured on, so two results can be told apart, and what
// `crowdprof --version` says.
#pragma once

#include <string>

namespace crowdprof {

struct Environment {
  std::string version, commit;
  std::string cpu;  // model name from /proc/cpuinfo
  unsigned cores = 0;
  std::string compiler, build_type;
  std::string simd;  // the SIMD target skinning runs on now (simd_target())
  // Whether its kernels fuse multiply-adds (skinning_kernels.h): digests of
  // runs that differ here differ by design. False in results written before
  // the kernels fused (environment.fused_multiply_add absent): they did not.
  bool fused_multiply_add = false;
};

Environment current_environment();

// The SIMD target the skinning kernels run on now, chosen at run time for the
// CPU or forced lower (skinning/simd_target.h): Highway's name, "AVX3" (AVX-512),
// "AVX2", "SSE4", "SSSE3", "SCALAR", ...
std::string simd_target();

// One line: "crowdprof 0.1.0 (commit 1a2b3c4d5e6f, Release, GNU 12.2.0, SIMD AVX2)".
std::string version_line();

}  // namespace crowdprof

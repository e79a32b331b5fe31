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
  std::string simd;  // the vector instructions the hot loops use (simd_target())
};

Environment current_environment();

// The widest vector instruction set this build's hot loops were compiled for
// ("AVX-512", "AVX2", "AVX", "SSE4.2", "SSE2", "NEON", "scalar"). There is no
// run-time dispatch yet, so it is fixed at compile time (-march).
std::string simd_target();

// One line: "crowdprof 0.1.0 (commit 1a2b3c4d5e6f, Release, GNU 12.2.0, SIMD AVX2)".
std::string version_line();

}  // namespace crowdprof

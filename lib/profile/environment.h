// What a result was measured on, so two results can be told apart.
#pragma once

#include <string>

namespace crowdprof {

struct Environment {
  std::string version, commit;
  std::string cpu;  // model name from /proc/cpuinfo
  unsigned cores = 0;
  std::string compiler, build_type;
  std::string simd;  // the SIMD target skinning runs on (skinning/simd_target.h)
};

Environment current_environment();

}  // namespace crowdprof

#include "measuring/environment.h"

#include <fstream>
#include <thread>

#include "skinning/simd_target.h"
#include "skinning/skinning_kernels.h"

// Defined in the source cmake/commit_stamp.cmake writes at every build.
const char* crowdprof_build_commit();

namespace crowdprof {

std::string simd_target() {
  return active_simd_target();
}

Environment current_environment() {
  Environment env;
  env.version = CROWDPROF_VERSION;
  env.commit = crowdprof_build_commit();
  env.compiler = CROWDPROF_COMPILER;
  env.build_type = CROWDPROF_BUILD_TYPE;
  env.simd = simd_target();
  env.fused_multiply_add = skinning_fuses_multiply_add();
  env.cores = std::thread::hardware_concurrency();
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    size_t colon = line.find(':');
    if (colon != std::string::npos) env.cpu = line.substr(line.find_first_not_of(" \t", colon + 1));
    break;
  }
  if (env.cpu.empty()) env.cpu = "unknown";
  return env;
}

std::string version_line() {
  std::string build_type = CROWDPROF_BUILD_TYPE;
  return std::string("crowdprof ") + CROWDPROF_VERSION + " (commit " + crowdprof_build_commit() + ", " +
         (build_type.empty() ? "no build type" : build_type) + ", " + CROWDPROF_COMPILER + ", SIMD " + simd_target() +
         ")";
}

}  // namespace crowdprof

// Lets valgrind run this binary on hosts whose CPU lacks RDTSCP (KVM guests
// that hide it). Debian 12's libhwy
// (1.0.3) measures its timer's resolution in a static initialiser, with
// RDTSCP, before main: valgrind 3.19 then stops with SIGILL (exit 132), so
// `check --metric instructions` and `./setup.sh valgrind` could not start.
// The binary links this file and exports the function (lib/CMakeLists.txt),
// so the dynamic linker binds libhwy's call here, as it would to a preloaded
// library. Only Highway's nanobenchmark reads the value, and crowdprof never
// runs it: its skinning dispatch does not time anything. The same binary then
// runs timed and counted.
#include <cstdint>

namespace hwy::platform {
uint64_t TimerResolution() {
  return 1;
}
}  // namespace hwy::platform

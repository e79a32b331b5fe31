#include "measuring/gpu_passes.h"

#include <cmath>

#include "measuring/stats.h"

namespace crowdprof {

GpuPassMedians gpu_pass_medians(const std::array<std::vector<double>, kGpuPassCount>& ms, uint32_t passes) {
  GpuPassMedians out;
  for (size_t p = 0; p < kGpuPassCount; ++p) {
    if (!pass_drawn(static_cast<GpuPass>(p), passes)) continue;
    std::vector<double> timed;
    for (double v : ms[p])
      if (std::isfinite(v)) timed.push_back(v);
    if (timed.empty()) continue;
    out.median[p] = quantile(timed, 0.5);
    out.sum += *out.median[p];
  }
  return out;
}

}  // namespace crowdprof

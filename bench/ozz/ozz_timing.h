// Timing both sides of ozz_driver in one process (docs/performance.md): blocks
// of frames alternating between ozz's jobs and crowdprof's over the same frame
// times, so that a host that changes speed hits both alike.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

namespace ozz_bench {

struct InterleavedTimes {
  std::vector<double> ozz_ms, crowdprof_ms;  // per frame
  std::vector<double> ratios;                // per block: crowdprof's sum over ozz's
};

inline double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Blocks of 10 frames, ozz's then crowdprof's over the same frames f, which
// side goes first alternating. Alternating every frame charges the side that
// runs second with the switch between the two, not its work
// (docs/experiments.md).
template <class OzzFrame, class CrowdprofFrame>
InterleavedTimes time_interleaved(size_t warmup, size_t frames, OzzFrame&& ozz_frame,
                                  CrowdprofFrame&& crowdprof_frame) {
  constexpr size_t kBlock = 10;
  InterleavedTimes times;
  for (size_t f = 0; f < warmup; ++f) {
    ozz_frame(f);
    crowdprof_frame(f);
  }
  for (size_t first = warmup, block = 0; first < warmup + frames; first += kBlock, ++block) {
    const size_t end = std::min(first + kBlock, warmup + frames);
    double sums[2] = {0, 0};  // ozz, crowdprof
    for (int side : {static_cast<int>(block % 2), static_cast<int>(1 - block % 2)})
      for (size_t f = first; f < end; ++f) {
        const auto start = std::chrono::steady_clock::now();
        if (side == 0)
          ozz_frame(f);
        else
          crowdprof_frame(f);
        const double ms = ms_since(start);
        sums[side] += ms;
        (side == 0 ? times.ozz_ms : times.crowdprof_ms).push_back(ms);
      }
    if (sums[0] > 0) times.ratios.push_back(sums[1] / sums[0]);
  }
  return times;
}

// Interpolated between order statistics, as crowdprof's medians are.
inline double quantile(std::vector<double> v, size_t num, size_t den) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double at = static_cast<double>((v.size() - 1) * num) / static_cast<double>(den);
  const size_t below = static_cast<size_t>(at);
  const double above = below + 1 < v.size() ? v[below + 1] : v[below];
  return v[below] + (above - v[below]) * (at - static_cast<double>(below));
}

}  // namespace ozz_bench

// The Mann-Whitney U test (Wilcoxon rank-sum), as Google Benchmark's
// compare.py uses to tell a real shift in frame times from noise: it ranks the
// samples instead of averaging them, so a few slow frames (a page fault, a
// context switch) cannot make a difference on their own.
#pragma once

#include <cstddef>
#include <span>

namespace crowdprof {

struct MannWhitney {
  double u = 0;  // U of the first sample: pairs (a, b) with a > b, ties counting 1/2
  double z = 0;  // U standardised; positive when the first sample tends to be larger
  double p = 1;  // two-sided p-value from the normal approximation
  size_t n1 = 0, n2 = 0;
};

// Normal approximation with the tie correction of the variance and a
// continuity correction of 1/2, as scipy.stats.mannwhitneyu(method="asymptotic").
// p is 1 when either sample is empty or all values are equal. The approximation
// is poor below about 8 samples a side; see kMannWhitneyMinSamples.
MannWhitney mann_whitney(std::span<const double> a, std::span<const double> b);

// Fewer samples a side than this and no shift can reach p < 0.05.
inline constexpr size_t kMannWhitneyMinSamples = 8;

}  // namespace crowdprof

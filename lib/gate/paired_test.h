// Statistics of paired measurements: an A/B of two builds run in ABBA groups
// gives one ratio per group, and a group's two builds saw the same moment of
// the machine, so the ratios are compared with zero change, not the two
// samples with each other (Mann-Whitney is for unpaired samples).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace crowdprof {

struct SignedRank {
  double w_plus = 0;   // sum of the ranks of |d| over the positive differences
  double p = 1;        // two-sided
  size_t n = 0;        // differences that are not zero
  bool exact = false;  // p from the exact distribution (no ties, n <= 25), else the normal approximation
};

// The Wilcoxon signed-rank test of `differences` against a median of zero.
// Zeros are dropped (Wilcoxon's convention), tied |d| get their mean rank;
// with ties or more than 25 differences p is the normal approximation with the
// tie correction and a continuity correction of 1/2, as
// scipy.stats.wilcoxon(method="approx", correction=True). p is 1 with no
// non-zero difference. Non-finite differences are not allowed.
SignedRank wilcoxon_signed_rank(std::span<const double> differences);

// The median of `values` and a percentile bootstrap interval of it
// (`resamples` draws of values.size() with replacement, seeded, so the same
// values give the same interval). All three are the one value for one value;
// zero for none.
struct MedianInterval {
  double median = 0, low = 0, high = 0;
};
MedianInterval bootstrap_median(std::span<const double> values, double confidence = 0.95, size_t resamples = 4000,
                                unsigned seed = 1);

// Holm's step-down correction: the k-th smallest of m p-values (from 0) times
// m - k, made monotone, capped at 1; in the order given.
std::vector<double> holm_adjust(std::span<const double> p);

}  // namespace crowdprof

// Summaries of per-frame samples, as reports print them.
#pragma once

#include <span>

namespace crowdprof {

struct Summary {
  double min = 0, median = 0, mean = 0, p95 = 0, p99 = 0, max = 0, stddev = 0;
};

// Median (p50), p95 and p99 by linear interpolation between order statistics; stddev is
// the sample standard deviation (n - 1). All zero for no samples.
Summary summarize(std::span<const double> samples);

// The value at quantile q (0..1) of the samples, interpolated.
double quantile(std::span<const double> samples, double q);

}  // namespace crowdprof

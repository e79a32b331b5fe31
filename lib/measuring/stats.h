// Summaries of per-frame samples, as reports print them.
#pragma once

#include <span>

namespace crowdprof {

struct Summary {
  double min = 0, median = 0, mean = 0, p95 = 0, p99 = 0, max = 0, stddev = 0;
};

// The median is a sample: of an even count, the lower of the two middle ones.
// So the median frame is a frame that was measured, and the profile table's
// categories (that frame's, report.h's median_frame) add up to the median every
// other table gives: one value, not 6.94 in one table and 6.985 in another.
// p95 and p99 by linear interpolation between order statistics; stddev is the
// sample standard deviation (n - 1). All zero for no samples.
Summary summarize(std::span<const double> samples);

// The value at quantile q (0..1) of the samples: at 0.5 the median above,
// else interpolated.
double quantile(std::span<const double> samples, double q);

}  // namespace crowdprof

#include "gate/mann_whitney.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace crowdprof {

MannWhitney mann_whitney(std::span<const double> a, std::span<const double> b) {
  MannWhitney result;
  result.n1 = a.size();
  result.n2 = b.size();
  if (a.empty() || b.empty()) return result;
  struct Sample {
    double value;
    bool first;
  };
  std::vector<Sample> all;
  all.reserve(a.size() + b.size());
  for (double v : a) all.push_back({v, true});
  for (double v : b) all.push_back({v, false});
  std::sort(all.begin(), all.end(), [](const Sample& x, const Sample& y) { return x.value < y.value; });

  // Ranks from 1, ties sharing the mean of their ranks; sum of t^3 - t over ties.
  double rank_sum_a = 0, ties = 0;
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    while (j < all.size() && all[j].value == all[i].value) ++j;
    double mean_rank = (static_cast<double>(i + 1) + static_cast<double>(j)) / 2.0;
    for (size_t k = i; k < j; ++k)
      if (all[k].first) rank_sum_a += mean_rank;
    double t = static_cast<double>(j - i);
    ties += t * t * t - t;
    i = j;
  }
  double n1 = static_cast<double>(a.size()), n2 = static_cast<double>(b.size()), n = n1 + n2;
  result.u = rank_sum_a - n1 * (n1 + 1) / 2.0;
  double mean = n1 * n2 / 2.0;
  double variance = n1 * n2 / 12.0 * ((n + 1) - ties / (n * (n - 1)));
  if (!(variance > 0)) return result;  // every value equal: no evidence of a shift
  double sigma = std::sqrt(variance);
  double distance = std::max(0.0, std::abs(result.u - mean) - 0.5);
  result.z = std::copysign(distance / sigma, result.u - mean);
  result.p = std::min(1.0, std::erfc(distance / sigma / std::sqrt(2.0)));
  return result;
}

}  // namespace crowdprof

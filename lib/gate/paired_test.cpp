#include "gate/paired_test.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "measuring/stats.h"

namespace crowdprof {

namespace {

// P(W+ <= w) under the null hypothesis, n untied ranks: the count of subsets
// of {1..n} whose sum is at most w, over 2^n.
double exact_lower_tail(size_t n, double w) {
  const size_t max_sum = n * (n + 1) / 2;
  std::vector<double> ways(max_sum + 1, 0.0);
  ways[0] = 1;
  for (size_t rank = 1; rank <= n; ++rank)
    for (size_t sum = max_sum; sum >= rank; --sum) ways[sum] += ways[sum - rank];
  double at_most = 0;
  for (size_t sum = 0; sum <= max_sum && static_cast<double>(sum) <= w + 1e-9; ++sum) at_most += ways[sum];
  return at_most / std::ldexp(1.0, static_cast<int>(n));
}

double normal_two_sided(double z) {
  return std::erfc(std::fabs(z) / std::sqrt(2.0));
}

}  // namespace

SignedRank wilcoxon_signed_rank(std::span<const double> differences) {
  std::vector<double> d;
  for (double x : differences)
    if (x != 0) d.push_back(x);
  SignedRank result;
  result.n = d.size();
  if (d.empty()) return result;
  std::vector<size_t> order(d.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return std::fabs(d[a]) < std::fabs(d[b]); });
  std::vector<double> rank(d.size());
  double tie_term = 0;  // sum of t^3 - t over groups of tied |d|
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && std::fabs(d[order[j + 1]]) == std::fabs(d[order[i]])) ++j;
    double mean_rank = (static_cast<double>(i) + static_cast<double>(j)) / 2 + 1;
    for (size_t k = i; k <= j; ++k) rank[order[k]] = mean_rank;
    double t = static_cast<double>(j - i + 1);
    tie_term += t * t * t - t;
    i = j + 1;
  }
  for (size_t i = 0; i < d.size(); ++i)
    if (d[i] > 0) result.w_plus += rank[i];
  const double n = static_cast<double>(d.size());
  const double total = n * (n + 1) / 2;
  if (tie_term == 0 && d.size() <= 25) {
    result.exact = true;
    double smaller = std::min(result.w_plus, total - result.w_plus);
    result.p = std::min(1.0, 2 * exact_lower_tail(d.size(), smaller));
    return result;
  }
  const double mean = total / 2;
  const double variance = n * (n + 1) * (2 * n + 1) / 24 - tie_term / 48;
  if (variance <= 0) return result;
  double deviation = result.w_plus - mean;
  deviation = std::copysign(std::max(0.0, std::fabs(deviation) - 0.5), deviation);
  result.p = std::min(1.0, normal_two_sided(deviation / std::sqrt(variance)));
  return result;
}

namespace {
// The midpoint of the two middle values of an even count: an estimate of the
// ratios' centre with no lean towards faster (stats.h's median is a sample, a
// frame, for what the tables show).
double midpoint_median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}
}  // namespace

MedianInterval bootstrap_median(std::span<const double> values, double confidence, size_t resamples, unsigned seed) {
  MedianInterval interval;
  if (values.empty()) return interval;
  interval.median = midpoint_median(std::vector<double>(values.begin(), values.end()));
  interval.low = interval.high = interval.median;
  if (values.size() == 1 || resamples == 0) return interval;
  std::mt19937 random(seed);
  std::uniform_int_distribution<size_t> pick(0, values.size() - 1);
  std::vector<double> medians(resamples), draw(values.size());
  for (double& median : medians) {
    for (double& x : draw) x = values[pick(random)];
    median = midpoint_median(draw);
  }
  const double tail = (1 - confidence) / 2;
  interval.low = quantile(medians, tail);
  interval.high = quantile(medians, 1 - tail);
  return interval;
}

std::vector<double> holm_adjust(std::span<const double> p) {
  std::vector<size_t> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
  std::vector<double> adjusted(p.size());
  double running = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    running = std::max(running, std::min(1.0, p[order[k]] * static_cast<double>(p.size() - k)));
    adjusted[order[k]] = running;
  }
  return adjusted;
}

}  // namespace crowdprof

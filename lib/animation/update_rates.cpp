#include "animation/update_rates.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace crowdprof {

uint8_t lod_shift(float screen_fraction, float every_1, float every_2, float every_4) {
  if (screen_fraction >= every_1) return 0;
  if (screen_fraction >= every_2) return 1;
  if (screen_fraction >= every_4) return 2;
  return kLodMaxShift;
}

BudgetPlan make_budget_plan(std::span<const float> screen_fraction, std::span<const uint8_t> base_shift,
                            std::span<const uint8_t> eligible) {
  BudgetPlan plan;
  for (size_t i = 0; i < screen_fraction.size(); ++i)
    if (eligible[i]) plan.order.push_back(static_cast<uint32_t>(i));
  std::stable_sort(plan.order.begin(), plan.order.end(),
                   [&](uint32_t a, uint32_t b) { return screen_fraction[a] < screen_fraction[b]; });
  size_t n = plan.order.size();
  for (uint32_t copy : plan.order) plan.base_shift.push_back(std::min(base_shift[copy], kMaxRateShift));
  plan.prefix.assign(kRateCount * (n + 1), 0.0);
  for (size_t s = 0; s < kRateCount; ++s)
    for (size_t r = 0; r < n; ++r) {
      int shift = std::min<int>(kMaxRateShift, plan.base_shift[r] + static_cast<int>(s));
      // Sums of powers of two this small are exact: the table does not depend
      // on the order it is summed in.
      plan.prefix[s * (n + 1) + r + 1] = plan.prefix[s * (n + 1) + r] + std::ldexp(1.0, -shift);
    }
  return plan;
}

uint8_t BudgetPlan::demoted_shift(size_t r, uint64_t demotions) const {
  uint64_t n = order.size();
  uint64_t round = demotions / n + (r < demotions % n ? 1 : 0);
  return static_cast<uint8_t>(std::min<uint64_t>(kMaxRateShift, base_shift[r] + round));
}

double BudgetPlan::expected_updates(uint64_t demotions) const {
  size_t n = order.size();
  if (n == 0) return 0.0;
  demotions = std::min(demotions, max_demotions());
  size_t round = static_cast<size_t>(demotions / n), first = static_cast<size_t>(demotions % n);
  const double* slower = &prefix[std::min(round + 1, kRateCount - 1) * (n + 1)];
  const double* rest = &prefix[round * (n + 1)];
  return slower[first] + (rest[n] - rest[first]);
}

bool AnimBudgetJob::Validate() const {
  return plan != nullptr && demotions != nullptr && budget_ms > 0 && std::isfinite(budget_ms) &&
         std::isfinite(measured_ms) && measured_ms >= 0;
}

bool AnimBudgetJob::Run() const {
  if (!Validate()) return false;
  if (updates_done == 0 || measured_ms <= 0 || plan->size() == 0) return true;
  double target = static_cast<double>(updates_done) * kBudgetAim * budget_ms / measured_ms;
  // The fewest doublings whose expected updates fit: expected_updates never
  // grows with more doublings, so a binary search finds it.
  uint64_t low = 0, high = plan->max_demotions();
  if (plan->expected_updates(high) > target) {
    *demotions = high;  // the slowest rates still do not fit: every copy at its slowest
    return true;
  }
  while (low < high) {
    uint64_t mid = low + (high - low) / 2;
    if (plan->expected_updates(mid) <= target)
      high = mid;
    else
      low = mid + 1;
  }
  *demotions = low;
  return true;
}

}  // namespace crowdprof

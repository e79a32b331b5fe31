// How often each copy's pose is updated (issue 13): update-rate LOD by size on
// screen, and the animation budget that lowers the rates of the copies
// smallest on screen until the Animations category fits. Pure functions of
// their inputs, so a run's choices can be replayed from its measured times.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace crowdprof {

// Periods are powers of two: a copy with shift s is updated every 2^s frames.
// The LOD alone uses shifts 0 to 3 (every 1, 2, 4, 8 frames); the budget may
// go on to kMaxRateShift (every 64 frames), never further: no copy waits more
// than 64 frames for its next pose.
constexpr uint8_t kLodMaxShift = 3;
constexpr uint8_t kMaxRateShift = 6;
constexpr size_t kRateCount = kMaxRateShift + 1;

// The LOD's shift of a copy whose box spans `screen_fraction` of the screen's
// height: 0 when >= every_1, 1 when >= every_2, 2 when >= every_4, else 3.
uint8_t lod_shift(float screen_fraction, float every_1, float every_2, float every_4);

// The budget's table for a crowd: the copies it may slow down, smallest on
// screen first, each with its LOD shift. Built once (it allocates); the
// per-frame job below only reads it.
struct BudgetPlan {
  std::vector<uint32_t> order;      // copies, smallest on screen first (ties: lower index first)
  std::vector<uint8_t> base_shift;  // per entry of order: the copy's LOD shift (0 without LOD)
  // prefix[s * (n + 1) + r]: expected updates per frame of order[0, r) when each
  // is slowed by s more doublings (capped at kMaxRateShift); exact in double.
  std::vector<double> prefix;

  size_t size() const { return order.size(); }
  // Doublings the budget can hand out before every copy is at the slowest rate.
  uint64_t max_demotions() const { return static_cast<uint64_t>(order.size()) * kMaxRateShift; }
  // Expected copy updates per frame after `demotions` doublings, handed out one
  // copy at a time in order, round after round (see demoted_shift).
  double expected_updates(uint64_t demotions) const;
  // The shift of entry r of order after `demotions` doublings: round
  // demotions / n for every copy, one more for the first demotions % n.
  uint8_t demoted_shift(size_t r, uint64_t demotions) const;
};

// `screen_fraction[i]` and `base_shift[i]` per copy; only copies with
// `eligible[i]` (posed by the mode) enter the plan.
BudgetPlan make_budget_plan(std::span<const float> screen_fraction, std::span<const uint8_t> base_shift,
                            std::span<const uint8_t> eligible);

// One frame of the budget's controller: from the Animations time measured on
// the previous frame and the copy updates it did, the doublings for the next
// frame. It aims at kBudgetAim of the budget (the headroom keeps the p95, not
// just the median, under it): the cost of an update is measured / updates, and
// the fewest doublings whose expected updates fit the aim are chosen. A frame
// that did no update, or measured nothing, keeps the doublings it had.
constexpr double kBudgetAim = 0.75;

struct AnimBudgetJob {
  const BudgetPlan* plan = nullptr;
  double budget_ms = 0;
  double measured_ms = 0;         // Animations of the previous frame
  uint64_t updates_done = 0;      // copy updates that frame
  uint64_t* demotions = nullptr;  // in: the previous frame's; out: this frame's

  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// Whether a copy with period 2^shift is due at `frame`: on its first frame
// (`last` < 0, never updated), on the frames where frame + offset is a multiple
// of the period (copies with different offsets take turns, so that a period's
// updates spread over its frames), and whenever `period` frames have passed
// since `last` (a copy whose period just changed never waits longer).
inline bool update_due(uint64_t frame, int64_t last, uint8_t shift, uint64_t offset) {
  const uint64_t period = uint64_t{1} << shift;
  return last < 0 || ((frame + offset) & (period - 1)) == 0 ||
         static_cast<int64_t>(frame) - last >= static_cast<int64_t>(period);
}

}  // namespace crowdprof

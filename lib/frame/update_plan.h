// Who takes a new pose this frame, at which time, and into which storage: the
// update-planning step of a frame (issue 13), before any pose is built.
// Update-rate LOD and the budget decide who is due; the time quantum rounds
// the time; sharing maps equal states to one evaluation. Sequential, and
// allocates nothing after it is made.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "animation/pose_sharing.h"
#include "animation/update_rates.h"
#include "asset/character.h"
#include "base/modes.h"
#include "measuring/counters.h"
#include "scene/crowd.h"

namespace crowdprof {

// One evaluation: the pose of `leader`'s action at `time`, written to pose
// storage `storage` (the leader's own, or with sharing the state's).
struct StateJob {
  uint32_t leader = 0, storage = 0;
  float time = 0;
  // Transitions: the weight of the leader's action (< 1 fading) and the time
  // of the action it fades from, as the state's key has them (snapped with
  // the time under a quantum), so that a storage holds the state its key names.
  float weight = 1, from_time = 0;
};

// How the run scheduled pose updates, over every frame run.
struct UpdateSchedule {
  uint64_t longest_gap = 0;  // most frames between two updates of one copy (0: none updated twice)
  // Copies posed in the last frame, by period: copies[s] are updated every 2^s frames.
  std::array<uint64_t, kRateCount> copies_by_rate{};
  uint64_t demotions = 0;  // the budget's doublings in the last frame
  // Changes of a copy's period over the run (the budget's: LOD periods follow
  // screen sizes, which never change): each one a visible change of pace.
  uint64_t rate_switches = 0;
};

// What a frame's plan reads.
struct PlanInput {
  uint64_t frame = 0;
  std::span<const float> times;      // per copy, this frame's (Logic)
  std::span<const uint8_t> visible;  // per copy, the last Scenegraph's
  // The Animations time the budget's controller compares with its budget:
  // the last frame's.
  double animations_ms = 0;
  // Transitions (frame/copy_store.h), per copy; empty without them: the
  // action played now, its weight (< 1 fading) and the action and time faded from.
  std::span<const uint16_t> actions, from_actions;
  std::span<const float> weights, from_times;
};

class UpdatePlanner {
 public:
  // For `crowd` of `characters` seen through `view_projection` (copies and
  // camera stand still: each copy's screen size, and its LOD period, are known
  // now); posed_on_cpu per character (PreparedCharacter).
  UpdatePlanner(std::span<const Character* const> characters, const Crowd& crowd, const glm::mat4& view_projection,
                const ModeSwitches& mode, std::vector<uint8_t> posed_on_cpu);

  // With a budget: its plan, from who is posed at all (once, after the first
  // Scenegraph stage, whose visibility culling reads).
  void start_budget(std::span<const uint8_t> visible);

  // This frame's evaluations; adds copies_updated, copies_held and the updates
  // by period to `counters`.
  std::span<const StateJob> plan(const PlanInput& input, Counters& counters);

  // Whether a copy is posed this frame: animated (not culled) and of a
  // character posed on the CPU.
  bool poses(size_t copy, std::span<const uint8_t> visible) const {
    return posed_on_cpu_[crowd_.kind[copy]] && (!mode_.animation_culling || visible[copy]);
  }
  std::span<const StateJob> jobs() const { return jobs_; }
  // Per copy: took a new pose in the last plan.
  bool updated(size_t copy) const { return updated_[copy] != 0; }
  // Per copy: updated every 2^shift frames.
  uint8_t shift(size_t copy) const { return shift_[copy]; }
  float screen_fraction(size_t copy) const { return screen_fraction_[copy]; }
  // The storage a copy shows: its own, or with sharing its state's.
  size_t storage_of(size_t copy) const { return mode_.share_poses ? sharing_.shown(copy) : copy; }
  // Every copy's storage with sharing; empty without (each shows its own).
  std::span<const uint32_t> shown() const {
    return mode_.share_poses ? sharing_.shown_storages() : std::span<const uint32_t>{};
  }
  const UpdateSchedule& schedule() const { return schedule_; }

 private:
  // The budget's doublings for this frame, from the last frame's time.
  void run_budget(const PlanInput& input);

  std::span<const Character* const> characters_;
  const Crowd& crowd_;
  ModeSwitches mode_;
  std::vector<uint8_t> posed_on_cpu_;   // per character
  bool any_posed_on_cpu_ = false;       // false (mode baked): plan() touches no copy
  std::vector<float> screen_fraction_;  // per copy
  std::vector<uint8_t> shift_;          // per copy: updated every 2^shift frames
  std::vector<uint8_t> updated_;        // per copy: took a new pose this frame
  std::vector<int64_t> last_update_;    // per copy: the frame it last took a pose (-1: never)
  std::vector<StateJob> jobs_;          // this frame's evaluations (capacity: one per copy)
  // Sharing, room for every copy: this frame's copies taking a new state, and its key.
  std::vector<uint32_t> changing_copies_;
  std::vector<uint64_t> changing_keys_;
  std::vector<float> changing_times_;                          // each changing copy's (snapped) time...
  std::vector<float> changing_weights_, changing_from_times_;  // ...and fade
  PoseSharing sharing_;
  BudgetPlan budget_plan_;
  uint64_t last_updates_ = 0;  // copy updates of the last frame, for the budget
  UpdateSchedule schedule_;
};

}  // namespace crowdprof

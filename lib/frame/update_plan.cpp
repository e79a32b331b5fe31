#include "frame/update_plan.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "animation/run_job.h"
#include "scene/screen_size.h"

namespace crowdprof {

UpdatePlanner::UpdatePlanner(std::span<const Character* const> characters, const Crowd& crowd,
                             const glm::mat4& view_projection, const ModeSwitches& mode,
                             std::vector<uint8_t> posed_on_cpu)
    : characters_(characters), crowd_(crowd), mode_(mode), posed_on_cpu_(std::move(posed_on_cpu)) {
  const size_t n = crowd.size();
  for (uint8_t posed : posed_on_cpu_) any_posed_on_cpu_ |= posed != 0;
  jobs_.reserve(n);
  updated_.assign(n, 0);
  last_update_.assign(n, -1);
  screen_fraction_.resize(n);
  shift_.assign(n, 0);
  const LodThresholds& lod = mode.lod;
  for (size_t i = 0; i < n; ++i) {
    screen_fraction_[i] = screen_height_fraction(view_projection, crowd.world_boxes[i]);
    if (mode.update_lod) shift_[i] = lod_shift(screen_fraction_[i], lod.every_1, lod.every_2, lod.every_4);
  }
  if (mode.share_poses) {
    sharing_.reset(crowd.kind, characters.size());
    changing_copies_.resize(n);
    changing_keys_.resize(n);
    changing_times_.resize(n);
    changing_weights_.resize(n);
    changing_from_times_.resize(n);
  }
}

namespace {

// A fading copy's state as one key: its character in the top 16 bits (a state
// lives in a storage of its character), bit 47 set (no unfading state has it:
// actions stay below 32,768), and a hash of the actions, times and weight. Two
// copies share a fading pose when all of those match.
uint64_t fade_key(uint16_t kind, uint16_t action, float time, uint16_t from, float from_time, float weight) {
  uint64_t h = 0xcbf29ce484222325ull;
  auto add = [&](uint64_t v) {
    h ^= v;
    h *= 0x100000001b3ull;
    h ^= h >> 29;
  };
  uint32_t bits[3];
  std::memcpy(&bits[0], &time, 4);
  std::memcpy(&bits[1], &from_time, 4);
  std::memcpy(&bits[2], &weight, 4);
  add(action);
  add(from);
  for (uint32_t b : bits) add(b);
  return (uint64_t{kind} << 48) | (uint64_t{1} << 47) | (h & ((uint64_t{1} << 47) - 1));
}

}  // namespace

void UpdatePlanner::start_budget(std::span<const uint8_t> visible) {
  if (mode_.anim_budget_ms <= 0) return;
  std::vector<uint8_t> eligible(crowd_.size());
  for (size_t i = 0; i < eligible.size(); ++i) eligible[i] = poses(i, visible);
  budget_plan_ = make_budget_plan(screen_fraction_, shift_, eligible);
}

void UpdatePlanner::run_budget(const PlanInput& input) {
  if (mode_.anim_budget_ms <= 0 || input.frame == 0) return;
  run_job(AnimBudgetJob{&budget_plan_, mode_.anim_budget_ms, input.animations_ms, last_updates_, &schedule_.demotions},
          "AnimBudgetJob");
  for (size_t r = 0; r < budget_plan_.size(); ++r) {
    const uint8_t shift = budget_plan_.demoted_shift(r, schedule_.demotions);
    uint8_t& current = shift_[budget_plan_.order[r]];
    schedule_.rate_switches += shift != current;
    current = shift;
  }
}

std::span<const StateJob> UpdatePlanner::plan(const PlanInput& input, Counters& counters) {
  run_budget(input);
  jobs_.clear();
  if (!any_posed_on_cpu_) return jobs_;  // no pose to build: a cost flat in the crowd (frustum gpu)
  size_t changes = 0;                    // copies taking a new state: changing_copies_, changing_keys_
  const bool share = mode_.share_poses;
  const double quantum = mode_.share_quantum_s;
  const bool culling = mode_.animation_culling;
  const uint64_t frame_number = input.frame;
  const auto frame = static_cast<int64_t>(frame_number);
  const std::span<const uint8_t> visible = input.visible;
  // Tallied in locals and stored once: the loop runs per copy, every frame.
  std::array<uint64_t, kRateCount> by_rate{}, updates_by_rate{};
  uint64_t held = 0, longest_gap = schedule_.longest_gap, every_frame = 0, updated_every_frame = 0;
  const size_t n = crowd_.size();
  for (size_t i = 0; i < n; ++i) {
    updated_[i] = 0;
    // poses(i), with the character's part read from one byte.
    if (!posed_on_cpu_[crowd_.kind[i]] || (culling && !visible[i])) continue;
    const uint8_t shift = shift_[i];
    // Most copies are updated every frame: that count lives in a register.
    if (shift == 0)
      ++every_frame;
    else
      ++by_rate[shift];
    // Copy i takes its turn at offset i: neighbours of one period alternate.
    const int64_t last = last_update_[i];
    if (!update_due(frame_number, last, shift, i)) {
      ++held;
      continue;
    }
    if (last >= 0) longest_gap = std::max<uint64_t>(longest_gap, frame - last);
    last_update_[i] = frame;
    updated_[i] = 1;
    if (shift == 0)
      ++updated_every_frame;
    else
      ++updates_by_rate[shift];
    const uint16_t action_index = input.actions.empty() ? crowd_.action[i] : input.actions[i];
    const std::vector<Action>& actions = characters_[crowd_.kind[i]]->actions;
    // The nearest multiple of the quantum from the action's start, never past its end.
    auto snapped = [&](const Action& action, float t) {
      if (quantum <= 0) return t;
      double steps = std::nearbyint(static_cast<double>(t - action.start) / quantum);
      return std::min(action.end, action.start + static_cast<float>(steps * quantum));
    };
    const float time = snapped(actions[action_index], input.times[i]);
    const bool fading = !input.weights.empty() && input.weights[i] < 1.0f;
    float weight = 1.0f, from_time = 0.0f;
    if (fading) {
      // The fade's weight snapped as its clock would be (quantum over the
      // fade's length), the old action's time as any time.
      weight = input.weights[i];
      const double blend_in = crowd_.transitions[i].blend_in_s;
      if (quantum > 0 && blend_in > 0) {
        const double step = quantum / blend_in;
        weight = std::min(1.0f, static_cast<float>(std::nearbyint(weight / step) * step));
      }
      from_time = snapped(actions[input.from_actions[i]], input.from_times[i]);
    }
    if (!share) {
      jobs_.push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(i), time, weight, from_time});
      continue;
    }
    uint64_t key;
    if (fading && weight < 1.0f) {
      key = fade_key(crowd_.kind[i], action_index, time, input.from_actions[i], from_time, weight);
    } else {
      uint32_t bits;
      std::memcpy(&bits, &time, sizeof bits);
      key = state_key(crowd_.kind[i], action_index, bits);
    }
    if (sharing_.key_of(sharing_.shown(i)) == key) continue;  // still in the state it shows
    changing_copies_[changes] = static_cast<uint32_t>(i);
    changing_times_[changes] = time;
    changing_weights_[changes] = weight;
    changing_from_times_[changes] = from_time;
    changing_keys_[changes++] = key;
  }
  by_rate[0] = every_frame;
  updates_by_rate[0] = updated_every_frame;
  schedule_.copies_by_rate = by_rate;
  schedule_.longest_gap = longest_gap;
  counters.copies_held += held;
  uint64_t updates = 0;
  for (size_t r = 0; r < kRateCount; ++r) {
    updates += updates_by_rate[r];
    counters.*kUpdatesByShift[r] += updates_by_rate[r];
  }
  counters.copies_updated += updates;
  last_updates_ = updates;
  if (!share) return jobs_;
  // Every release before any take: a state that one copy leaves and another
  // enters this frame keeps its storage, and there is always room.
  std::span<const uint32_t> copies = std::span(changing_copies_).first(changes);
  sharing_.release(copies);
  for (size_t c = 0; c < changes;) {
    // Copies taking one key one after another (a shared action: all of them).
    const uint64_t key = changing_keys_[c];
    size_t end = c + 1;
    while (end < changes && changing_keys_[end] == key) ++end;
    bool evaluate = false;
    uint32_t storage = sharing_.take(copies.subspan(c, end - c), key, &evaluate);
    if (evaluate)
      jobs_.push_back({copies[c], storage, changing_times_[c], changing_weights_[c], changing_from_times_[c]});
    c = end;
  }
  return jobs_;
}

}  // namespace crowdprof

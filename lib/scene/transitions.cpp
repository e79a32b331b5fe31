#include "scene/transitions.h"

#include <algorithm>
#include <cmath>

namespace crowdprof {

namespace {

// SplitMix64's finaliser: a well-mixed 64-bit value from any input, so that
// each (seed, stream, change, what) is its own draw with no state to keep.
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

float ActionClock::local_time(const Action& clip, double t) const {
  const double duration = clip.duration();
  const double local = duration > 0 ? std::fmod(static_cast<double>(phase) + (t - started), duration) : 0.0;
  return clip.start + static_cast<float>(local);
}

TransitionSchedule::TransitionSchedule(std::span<const Character* const> characters, const Crowd& crowd, uint32_t seed)
    : TransitionSchedule(characters, crowd, TransitionTiming{}, seed) {
  if (!crowd.transitions.empty()) timing_ = crowd.transitions;
  schedule_first_changes();
}

TransitionSchedule::TransitionSchedule(std::span<const Character* const> characters, const Crowd& crowd,
                                       TransitionTiming timing, uint32_t seed)
    : characters_(characters), crowd_(&crowd), timing_(crowd.size(), timing), seed_(seed) {
  copies_.resize(crowd.size());
  next_.resize(crowd.size());
  for (size_t i = 0; i < crowd.size(); ++i) {
    CopyAction& c = copies_[i];
    c.now = {crowd.action[i], crowd.phase[i], 0.0};
    c.before = c.now;
  }
  schedule_first_changes();
}

void TransitionSchedule::schedule_first_changes() {
  // A schedule already running when the run starts: the first change comes
  // a random part of an interval in, so changes are as common from frame 0
  // on. No copy is mid-fade at 0: fades reach their share after blend_in
  // (docs/modes.md says to warm up that long).
  for (size_t i = 0; i < copies_.size(); ++i)
    next_[i] = timing_[i].mean_s > 0 ? draw(crowd_->schedule_stream[i], 0, 3) * interval(i, 1)
                                     : std::numeric_limits<double>::infinity();
}

double TransitionSchedule::draw(uint32_t stream, uint32_t change, uint32_t what) const {
  const uint64_t bits = mix(mix(mix(seed_) ^ stream) ^ (uint64_t{change} << 8 | what));
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

double TransitionSchedule::interval(size_t copy, uint32_t change) const {
  const double mean = timing_[copy].mean_s;
  if (!(mean > 0)) return std::numeric_limits<double>::infinity();
  return mean * (0.5 + draw(crowd_->schedule_stream[copy], change, 0));
}

void TransitionSchedule::change(size_t copy, double at) {
  CopyAction& c = copies_[copy];
  const uint32_t stream = crowd_->schedule_stream[copy];
  const uint32_t n = ++c.changes;
  const std::vector<Action>& actions = characters_[crowd_->kind[copy]]->actions;
  c.before = c.now;
  c.changed_at = at;
  uint16_t next = c.now.action;
  if (actions.size() > 1) {
    // Evenly among the others: a draw over all but the current, stepping past it.
    auto pick = static_cast<uint16_t>(std::min<double>(draw(stream, n, 1) * static_cast<double>(actions.size() - 1),
                                                       static_cast<double>(actions.size() - 2)));
    next = pick >= c.now.action ? static_cast<uint16_t>(pick + 1) : pick;
  }
  const float duration = actions.empty() ? 0.0f : actions[next].duration();
  c.now = {next, static_cast<float>(draw(stream, n, 2)) * duration, at};
  next_[copy] = at + interval(copy, n + 1);
}

void TransitionSchedule::advance(double t) {
  for (size_t i = 0; i < copies_.size(); ++i) {
    const double blend = timing_[i].blend_in_s;
    while (t >= next_[i]) change(i, next_[i]);
    CopyAction& c = copies_[i];
    const double since = t - c.changed_at;
    c.weight = blend > 0 && since < blend ? static_cast<float>(since / blend) : 1.0f;
  }
}

}  // namespace crowdprof

// When each copy of a crowd changes action, and what it fades from (issue 53):
// game crowds go from idle to walk to run with a crossfade, where the thesis's
// copies loop one action. A copy changes after an interval drawn from the
// seed, uniformly between half and one and a half times the mean (the first
// a random part of one, as if the schedule had been running before the run),
// so that about blend_in / mean of the copies are fading at any moment. Its next
// action is another of its character's, drawn evenly (a character of one
// action re-enters it), at a random phase. Copies of a group with shared
// actions draw from one stream (Crowd::schedule_stream) and change as one.
// Deterministic: the seed, the stream and the time give the same answer in
// every mode and on any thread.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "asset/character.h"
#include "scene/crowd.h"

namespace crowdprof {

// An action on a copy's clock: at time t (seconds since the run began) it is
// phase + (t - started) seconds in, looping over its duration.
struct ActionClock {
  uint16_t action = 0;
  float phase = 0.0f;
  double started = 0.0;

  // Seconds on the clip's own clock (from clip.start) at time t; `clip` is
  // the character's action numbered `action`.
  float local_time(const Action& clip, double t) const;
};

// Where a copy stands at one moment: its action and, while it fades into it,
// the action it leaves and the new one's weight (0 at the change, 1 once the
// fade is over).
struct CopyAction {
  ActionClock now, before;
  double changed_at = -std::numeric_limits<double>::infinity();  // the last change
  float weight = 1.0f;                                           // of `now`; < 1 while fading from `before`
  uint32_t changes = 0;

  bool fading() const { return weight < 1.0f; }
};

class TransitionSchedule {
 public:
  // For `crowd` of `characters`, its first actions and phases as the crowd
  // has them, each copy on its group's timing (crowd.transitions; a mean of
  // 0 keeps its action); times move forward from 0.
  TransitionSchedule(std::span<const Character* const> characters, const Crowd& crowd, uint32_t seed);
  // The same with one timing for every copy.
  TransitionSchedule(std::span<const Character* const> characters, const Crowd& crowd, TransitionTiming timing,
                     uint32_t seed);

  // Moves every copy to time t (seconds since the run began, not before the
  // last call's). Allocates nothing.
  void advance(double t);
  const CopyAction& operator[](size_t copy) const { return copies_[copy]; }
  size_t size() const { return copies_.size(); }

  // The interval before change `change` of copy `copy`'s stream (change 1 is
  // the first): infinite when it keeps its action. And the uniform draw in
  // [0, 1) of a stream that picks what follows a change.
  double interval(size_t copy, uint32_t change) const;
  double draw(uint32_t stream, uint32_t change, uint32_t what) const;

 private:
  void change(size_t copy, double at);
  void schedule_first_changes();

  std::span<const Character* const> characters_;
  const Crowd* crowd_;
  std::vector<TransitionTiming> timing_;  // per copy
  uint32_t seed_;
  std::vector<CopyAction> copies_;
  std::vector<double> next_;  // per copy, when it changes next
};

}  // namespace crowdprof

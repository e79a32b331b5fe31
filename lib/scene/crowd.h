// The stress scene: copies of one or more characters on a grid, each with its
// action and its phase in that action.
#pragma once

#include <cstdint>
#include <optional>

#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/anim_layers.h"
#include "asset/character.h"
#include "scene/bounds.h"

namespace crowdprof {

enum class ActionChoice : uint8_t {
  Shared,    // every copy plays the same action, in phase (the thesis's scene)
  Random,    // a random action and phase per copy (the thesis's -random)
  Weighted,  // a random phase, and an action drawn from a weighted list
};

// How often copies change action and how long they fade (issue 53;
// scene/transitions.h): after an interval around mean_s, over blend_in_s.
struct TransitionTiming {
  double mean_s = 0.0;      // 0: the copy keeps its action
  double blend_in_s = 0.0;  // >= 0, at most half of mean_s: fades never overlap
};

// The copies of one character and what they play.
struct CrowdGroup {
  size_t character = 0;  // index into the crowd's characters
  size_t copies = 0;
  ActionChoice actions = ActionChoice::Shared;
  int shared_action = 0;        // with Shared: the action every copy plays
  std::vector<double> weights;  // with Weighted: one per action of the character, not all zero
  // The group's own transitions (a scene file's "transitions"), else the crowd's.
  std::optional<TransitionTiming> transitions;
  // The group's own layers (a scene file's "layers"), else the mode's anim_layers.
  std::optional<std::vector<AnimLayer>> layers;
};

// Where copies stand: a grid of rows across X, front row at +Z.
struct CrowdLayout {
  float spacing = 0.0f;      // metres between neighbours; 0: the largest animated footprint x 1.1
  size_t rows = 0;           // 0: as many as make the grid about 1.6 times as wide as deep
  float jitter = 0.0f;       // each copy moved up to this many metres in X and Z...
  uint32_t jitter_seed = 1;  // ...by a generator of this seed
};

struct CrowdOptions {
  size_t copies = 160;  // in all
  // Without groups: one group of character 0 with these choices.
  ActionChoice actions = ActionChoice::Shared;
  int shared_action = 0;
  uint32_t seed = 1;  // random actions and phases
  // Several characters: their copies are scaled to `copies` in all when the
  // counts add up to something else (a crowd-size sweep of a mixed scene).
  std::vector<CrowdGroup> groups;
  CrowdLayout layout;
  // The transitions of groups that state none (--transitions, --blend-in).
  TransitionTiming transitions;
};

// The groups `options` describes, with counts that add up to options.copies
// (scaled, largest remainders first).
std::vector<CrowdGroup> crowd_groups(const CrowdOptions& options);

// Immutable once made: where each copy stands, which character it is, and
// what it plays.
struct Crowd {
  std::vector<glm::mat4> world;  // per copy
  std::vector<uint16_t> kind;    // per copy, index into the characters
  std::vector<uint16_t> action;  // per copy, index into its character's actions
  std::vector<float> phase;      // per copy, seconds into its action at t = 0
  // Per copy, which random stream its action changes are drawn from
  // (scene/transitions.h): its own (its index), or with shared actions its
  // group's (past every copy's), so that the group changes as one.
  std::vector<uint32_t> schedule_stream;
  // Per copy, its group's transitions; empty when no copy changes action.
  std::vector<TransitionTiming> transitions;
  std::vector<Aabb> character_boxes;  // per character: animated_bounds
  std::vector<Aabb> world_boxes;      // per copy
  Aabb crowd_box;                     // around every copy
  size_t columns = 0, rows = 0;
  size_t size() const { return world.size(); }
};

// Lays the copies out in rows across X, front row at +Z, all facing +Z, spaced
// by the characters' largest animated footprint; 16 columns by 10 rows for 160,
// as wide as about 1.6 times deep. The characters of a mixed crowd are spread
// evenly over the grid in proportion to their counts. Random choices come from
// the seeds alone.
Crowd make_crowd(std::span<const Character* const> characters, const CrowdOptions& options);
Crowd make_crowd(const Character& character, const CrowdOptions& options);

}  // namespace crowdprof

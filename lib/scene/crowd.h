// The stress scene: copies of one character on a grid, each with its action
// and its phase in that action.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "asset/character.h"
#include "scene/bounds.h"

namespace crowdprof {

enum class ActionChoice : uint8_t {
  Shared,  // every copy plays the same action, in phase (the thesis's scene)
  Random,  // a random action and phase per copy (the thesis's -random)
};

struct CrowdOptions {
  size_t copies = 160;
  ActionChoice actions = ActionChoice::Shared;
  uint32_t seed = 1;
  int shared_action = 0;  // with Shared: the action every copy plays
};

// Immutable once made: where each copy stands and what it plays.
struct Crowd {
  std::vector<glm::mat4> world;     // per copy
  std::vector<uint16_t> action;     // per copy, index into Character::actions
  std::vector<float> phase;         // per copy, seconds into its action at t = 0
  Aabb character_box;               // animated_bounds of the character
  std::vector<Aabb> world_boxes;    // per copy
  Aabb crowd_box;                   // around every copy
  size_t columns = 0, rows = 0;
  size_t size() const { return world.size(); }
};

// Lays the copies out in rows across X, front row at +Z, all facing +Z, spaced
// by the character's animated footprint; 16 columns by 10 rows for 160, as
// wide as about 1.6 times deep. Random choices come from `seed` alone.
Crowd make_crowd(const Character& character, const CrowdOptions& options);

}  // namespace crowdprof

// The characters tests share, made once per test binary: generated in memory,
// so a test needs no file and no sample assets.
#pragma once

#include "asset/character.h"
#include "gen/humanoid.h"

namespace crowdprof::test {

// A humanoid of 30 joints and 800 vertices with 7 actions: every stage of a
// frame has work to do, at a small fraction of the default scene's cost.
inline const Character& small_humanoid() {
  static const Character character = generate_humanoid({30, 800, 7});
  return character;
}

}  // namespace crowdprof::test

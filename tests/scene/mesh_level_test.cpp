// The mesh level a copy's size picks (scene/screen_size.h): one level per
// threshold below, at most the levels there are, and a band above each
// threshold in which a coarser copy stays coarse (no flicker at a threshold).
#include <gtest/gtest.h>

#include <cmath>

#include "scene/screen_size.h"

using namespace crowdprof;

namespace {
constexpr float kAt[3] = {0.25f, 0.125f, 0.0625f};
uint8_t pick(float fraction, uint8_t current, size_t levels = 4) {
  return mesh_level_for(fraction, current, kAt, 0.15f, levels);
}
}  // namespace

TEST(MeshLevel, OneLevelPerThresholdBelow) {
  EXPECT_EQ(pick(0.5f, 0), 0);
  EXPECT_EQ(pick(0.25f, 0), 0);
  EXPECT_EQ(pick(0.2f, 0), 1);
  EXPECT_EQ(pick(0.1f, 0), 2);
  EXPECT_EQ(pick(0.01f, 0), 3);
  EXPECT_EQ(pick(0.0f, 0), 3);
}

TEST(MeshLevel, NeverPastTheLevelsACharacterHas) {
  EXPECT_EQ(pick(0.01f, 0, 2), 1);
  EXPECT_EQ(pick(0.01f, 0, 1), 0);
  EXPECT_EQ(pick(0.01f, 3, 1), 0);
  EXPECT_EQ(pick(0.3f, 3, 3), 0);
}

TEST(MeshLevel, CoarserAtOnceFinerOnlyPastTheBand) {
  // Coarsening: as soon as the copy is below the threshold.
  EXPECT_EQ(pick(0.2499f, 0), 1);
  // Refining from level 1: not at 0.26 (inside the band up to 0.2875), at 0.29.
  EXPECT_EQ(pick(0.26f, 1), 1);
  EXPECT_EQ(pick(0.29f, 1), 0);
  // From level 3, a copy at 0.13 is past threshold 2 (0.0625 x 1.15) but inside threshold 1's band.
  EXPECT_EQ(pick(0.13f, 3), 2);
  EXPECT_EQ(pick(0.15f, 3), 1);
  // Going up and down across a threshold: the level changes twice, not at every step.
  uint8_t level = 0;
  int switches = 0;
  for (float f : {0.26f, 0.24f, 0.26f, 0.24f, 0.26f, 0.3f}) {
    uint8_t next = pick(f, level);
    switches += next != level;
    level = next;
  }
  EXPECT_EQ(switches, 2);
  EXPECT_EQ(level, 0);
}

TEST(MeshLevel, ANanSizeKeepsTheLevel) {
  EXPECT_EQ(pick(std::nanf(""), 2), 2);
  EXPECT_EQ(pick(std::nanf(""), 3, 2), 1);
}

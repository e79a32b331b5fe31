// Baked animation (mode `baked`): the bake job samples where it says, the
// interpolated palette is what the vertex shader computes, and the deviation
// measure agrees with a case worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "animation/bake.h"
#include "animation/binding.h"
#include "animation/pose.h"
#include "asset/gltf_loader.h"
#include "skinning/bake_deviation.h"
#include "skinning/skinning_plan.h"
#include "one_joint_character.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

// One joint at the origin that turns 90 degrees about y over one second, and
// one vertex at (1, 0, 0) bound to it: the vertex sweeps a quarter of the unit
// circle, to (0, 0, -1). A second vertex, 2 up on the axis, never moves.
Character turning_joint() {
  const float h = std::sqrt(0.5f);
  return test::one_joint_character("turn", {glm::vec3(1, 0, 0), glm::vec3(0, 2, 0)},
                                   {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}, {0, 1, 0}, ChannelPath::Rotation,
                                   {0, 0, 0, 1, 0, h, 0, h});  // x y z w: identity, then 90 degrees about y
}

std::vector<std::span<const int32_t>> targets_of(const std::vector<ActionBindings>& bindings) {
  std::vector<std::span<const int32_t>> targets;
  for (const ActionBindings& b : bindings) targets.emplace_back(b.targets);
  return targets;
}

}  // namespace

TEST(Bake, IntervalsCoverTheActionAtTheRate) {
  Action a;
  a.start = 0.5f;
  a.end = 1.5f;
  EXPECT_EQ(baked_intervals(a, 30.0f), 30u);  // exactly 30, not 31 from rounding
  EXPECT_EQ(baked_intervals(a, 29.5f), 30u);  // rounded up: the step stays <= 1 / rate
  EXPECT_EQ(baked_samples(a, 30.0f), 31u);
  a.end = a.start;
  EXPECT_EQ(baked_intervals(a, 30.0f), 1u);  // a pose, not an action: still two samples
  a.end = 1.5f;
  EXPECT_FLOAT_EQ(baked_position(a, 30, 1.0f), 15.0f);
  EXPECT_FLOAT_EQ(baked_position(a, 30, 9.0f), 30.0f);  // clamped to the last sample
  EXPECT_FLOAT_EQ(baked_position(a, 30, 0.0f), 0.0f);
}

TEST(Bake, SamplesAreTheExactPosesAtTheirTimes) {
  Character c = turning_joint();
  std::vector<ActionBindings> bindings = {bind_action(c.skeleton, c.actions[0])};
  BakedCharacter baked;
  ASSERT_TRUE(bake_character(c, targets_of(bindings), 2.0f, &baked));
  ASSERT_EQ(baked.samples(), 3u);  // 0, 45 and 90 degrees
  for (size_t s = 0; s < 3; ++s) {
    glm::vec4 p = baked.matrices[s] * glm::vec4(1, 0, 0, 1);
    float angle = glm::radians(45.0f * static_cast<float>(s));
    EXPECT_NEAR(p.x, std::cos(angle), 1e-6) << s;
    EXPECT_NEAR(p.z, -std::sin(angle), 1e-6) << s;
  }
  // Halfway between samples 0 and 1, the palette is the average of theirs.
  SkinMatrix mid;
  ASSERT_TRUE((BakedPaletteJob{baked.matrices, 1, 0.5f, std::span(&mid, 1)}.Run()));
  glm::vec4 p = mid * glm::vec4(1, 0, 0, 1);
  EXPECT_NEAR(p.x, (1.0f + std::sqrt(0.5f)) / 2, 1e-6);
  EXPECT_NEAR(p.z, -std::sqrt(0.5f) / 2, 1e-6);
  // At the last sample: exactly the last one (no interval past it).
  ASSERT_TRUE((BakedPaletteJob{baked.matrices, 1, 2.0f, std::span(&mid, 1)}.Run()));
  EXPECT_EQ(mid, baked.matrices[2]);
}

// A fade mixes two baked palettes matrix by matrix (what baked.vert does):
// weight 0 is the action now, 1 the action left, between them the mean.
TEST(Bake, AFadeMixesTwoBakedPalettesByItsWeight) {
  Character c = turning_joint();
  std::vector<ActionBindings> bindings = {bind_action(c.skeleton, c.actions[0])};
  BakedCharacter baked;
  ASSERT_TRUE(bake_character(c, targets_of(bindings), 2.0f, &baked));
  SkinMatrix now, from;
  auto fade = [&](float now_at, float from_at, float weight) {
    return BakedFadeJob{
        {baked.matrices, 1, now_at, std::span(&now, 1)}, {baked.matrices, 1, from_at, std::span(&from, 1)}, weight};
  };
  ASSERT_TRUE(fade(0.0f, 2.0f, 0.0f).Run());
  EXPECT_EQ(now, baked.matrices[0]);
  ASSERT_TRUE(fade(0.0f, 2.0f, 1.0f).Run());
  EXPECT_EQ(now, baked.matrices[2]);
  ASSERT_TRUE(fade(0.0f, 2.0f, 0.25f).Run());
  const SkinMatrix expected = baked.matrices[0] * 0.75f + baked.matrices[2] * 0.25f;
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) EXPECT_NEAR(now[col][row], expected[col][row], 1e-6) << col << " " << row;
  EXPECT_FALSE(fade(0.0f, 2.0f, 1.5f).Validate());
  EXPECT_FALSE(fade(0.0f, 2.0f, NAN).Validate());
  BakedFadeJob same_output = fade(0.0f, 2.0f, 0.5f);
  same_output.from.output = same_output.now.output;
  EXPECT_FALSE(same_output.Validate()) << "the action left needs its own scratch";
}

TEST(Bake, JobsRefuseWhatTheyCannotFill) {
  Character c = turning_joint();
  std::vector<ActionBindings> bindings = {bind_action(c.skeleton, c.actions[0])};
  LocalPose pose;
  reset_to_rest(c.skeleton, &pose);
  SamplingCursor cursor;
  reset_cursor(c.actions[0], &cursor);
  std::vector<glm::mat4> model(1);
  std::vector<SkinMatrix> out(3);
  BakeJob job{&c.skeleton, &c.actions[0], bindings[0].targets, 2.0f, &cursor, &pose, model, out};
  EXPECT_TRUE(job.Validate());
  job.output = std::span(out).first(2);  // one sample short
  EXPECT_FALSE(job.Run());
  job.output = out;
  job.rate_hz = 0.0f;
  EXPECT_FALSE(job.Validate());
  job.rate_hz = NAN;
  EXPECT_FALSE(job.Validate());
  SkinMatrix one;
  EXPECT_FALSE((BakedPaletteJob{std::span(out).first(1), 1, 0.0f, std::span(&one, 1)}.Validate()));  // one sample
}

// Worked by hand: linear interpolation between two rotations of a unit vector
// by angle a lands on the chord, whose middle is 1 - cos(a / 2) inside the arc.
// At 1 Hz the interval is the whole 90 degrees: 1 - cos 45 = 0.292893; at 2 Hz,
// 45 degrees: 1 - cos 22.5 = 0.076120. The vertex 2 units up on the axis of
// turning never moves, and the height is 2 (y from 0 to 2).
// (The largest deviation is at the middle probe; the quarter probes give
// |(0.75, 0.25) - (cos 22.5, sin 22.5)| = 0.2187 at 1 Hz, less.)
TEST(Bake, DeviationMatchesTheCaseWorkedByHand) {
  Character c = turning_joint();
  std::vector<ActionBindings> bindings = {bind_action(c.skeleton, c.actions[0])};
  SkinningPlan plan;
  ASSERT_EQ(build_skinning_plan(c.mesh, 1, &plan), "");
  for (auto [rate, expected] : {std::pair{1.0f, 1.0 - std::cos(M_PI / 4)}, std::pair{2.0f, 1.0 - std::cos(M_PI / 8)}}) {
    BakedCharacter baked;
    ASSERT_TRUE(bake_character(c, targets_of(bindings), rate, &baked));
    BakeDeviation d = measure_bake_deviation(c, targets_of(bindings), baked, plan);
    EXPECT_NEAR(d.model_units, expected, 2e-6) << rate;
    EXPECT_FLOAT_EQ(d.height, 2.0f);
    EXPECT_NEAR(d.fraction_of_height(), expected / 2, 1e-6) << rate;
  }
}

TEST(Bake, DeviationShrinksWithTheRateForTheDefaultCharacter) {
  Character c = load_character((test::source_dir() / "scenes" / "humanoid.glb").string());
  std::vector<ActionBindings> bindings;
  for (const Action& a : c.actions) bindings.push_back(bind_action(c.skeleton, a));
  SkinningPlan plan;
  ASSERT_EQ(build_skinning_plan(c.mesh, c.skeleton.joint_count(), &plan), "");
  float previous = INFINITY;
  for (float rate : {10.0f, 30.0f, 120.0f}) {
    BakedCharacter baked;
    ASSERT_TRUE(bake_character(c, targets_of(bindings), rate, &baked));
    BakeDeviation d = measure_bake_deviation(c, targets_of(bindings), baked, plan);
    std::cout << "[ info ] humanoid baked at " << rate << " Hz: " << d.model_units << " model units, "
              << 100 * d.fraction_of_height() << "% of its height " << d.height << "\n";
    EXPECT_GT(d.model_units, 0.0f) << rate;
    EXPECT_LT(d.model_units, previous) << rate;
    previous = d.model_units;
  }
}

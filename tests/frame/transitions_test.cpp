// Transitions (issue 53): copies change action on a schedule drawn from the
// seed and fade into the next; about blend_in / mean of them fade at once; a
// shared group changes as one; no pose jumps in a fade; master, culled and
// threaded compute the same poses on any thread count; exact modes draw fading
// copies exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "animation/binding.h"
#include "animation/exact_palette.h"
#include "frame/crowd_bench.h"
#include "render_support.h"
#include "scene/transitions.h"

using namespace crowdprof;

namespace {

BenchConfig fading(const std::string& mode, Crossfade crossfade, int threads = 2, size_t copies = 40) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode.transitions_s = 1.0;
  config.mode.blend_in_s = 0.4;
  config.mode.crossfade = crossfade;
  config.mode_name = mode;
  config.threads = threads;
  config.crowd.copies = copies;
  config.crowd.actions = ActionChoice::Random;
  return config;
}

}  // namespace

TEST(Transitions, AboutBlendInOverMeanOfTheCopiesFadeAtOnce) {
  const Character* humanoid[] = {&test::default_humanoid()};
  CrowdOptions options;
  options.copies = 1000;
  options.actions = ActionChoice::Random;
  const Crowd crowd = make_crowd(humanoid, options);
  TransitionSchedule schedule(humanoid, crowd, {2.0, 0.5}, 7);
  double fading = 0, samples = 0;
  uint32_t changes = 0;
  for (int frame = 0; frame < 600; ++frame) {
    schedule.advance(frame / 60.0);
    for (size_t i = 0; i < schedule.size(); ++i) {
      fading += schedule[i].fading();
      // Another action each time: the humanoid has three.
      if (schedule[i].changes > 0) EXPECT_NE(schedule[i].now.action, schedule[i].before.action);
    }
    samples += static_cast<double>(schedule.size());
  }
  for (size_t i = 0; i < schedule.size(); ++i) changes += schedule[i].changes;
  EXPECT_NEAR(fading / samples, 0.5 / 2.0, 0.02);
  EXPECT_NEAR(changes / 1000.0, 10.0 / 2.0, 0.5) << "a change every 2 s on average over 10 s";
}

TEST(Transitions, ASharedGroupChangesAsOneAndTheSeedDecides) {
  const Character* humanoid[] = {&test::default_humanoid()};
  CrowdOptions options;
  options.copies = 50;
  const Crowd crowd = make_crowd(humanoid, options);  // shared actions
  TransitionSchedule a(humanoid, crowd, {1.0, 0.25}, 3), b(humanoid, crowd, {1.0, 0.25}, 3),
      other(humanoid, crowd, {1.0, 0.25}, 4);
  bool differs = false;
  for (int frame = 0; frame < 300; frame += 7) {
    a.advance(frame / 60.0), b.advance(frame / 60.0), other.advance(frame / 60.0);
    for (size_t i = 1; i < a.size(); ++i) {
      ASSERT_EQ(a[i].now.action, a[0].now.action);
      ASSERT_EQ(a[i].weight, a[0].weight);
      ASSERT_EQ(a[i].now.phase, a[0].now.phase);
    }
    EXPECT_EQ(a[0].now.action, b[0].now.action);
    EXPECT_EQ(a[0].changed_at, b[0].changed_at);
    differs |= a[0].changed_at != other[0].changed_at;
  }
  EXPECT_TRUE(differs) << "another seed, another schedule";
}

TEST(Transitions, EveryCpuModeComputesTheSamePosesOnAnyThreadCount) {
  for (Crossfade crossfade : {Crossfade::Sampled, Crossfade::Frozen}) {
    std::string digest;
    size_t fades = 0;
    for (const char* mode : {"master", "culled", "threaded"})
      for (int threads : {1, 2}) {
        if (std::string(mode) != "threaded" && threads == 2) continue;
        CrowdBench bench(test::default_humanoid(), fading(mode, crossfade, threads));
        FrameRecord last;
        for (int f = 0; f < 80; ++f) last = bench.step();
        if (digest.empty()) digest = bench.digest(), fades = last.counters.fades;
        EXPECT_EQ(bench.digest(), digest) << mode << " on " << threads << " threads, " << to_string(crossfade);
        if (std::string(mode) == "threaded") EXPECT_GT(last.counters.fades, 0u) << "the last frame is mid-fade";
      }
  }
}

TEST(Transitions, SampledFadesSampleTwoActionsAndFrozenOnesOneAFrame) {
  CrowdBench sampled(test::default_humanoid(), fading("threaded", Crossfade::Sampled));
  CrowdBench frozen(test::default_humanoid(), fading("threaded", Crossfade::Frozen));
  uint64_t sampled_extra = 0, frozen_extra = 0, fades = 0;
  for (int f = 0; f < 120; ++f) {
    const Counters s = sampled.step().counters, z = frozen.step().counters;
    ASSERT_EQ(s.fades, z.fades) << "one schedule";
    ASSERT_EQ(s.joints_blended, s.fades * test::default_humanoid().skeleton.joint_count());
    sampled_extra += s.actions_sampled - s.poses_updated;
    frozen_extra += z.actions_sampled - z.poses_updated;
    fades += s.fades;
    EXPECT_EQ(s.actions_sampled - s.poses_updated, s.fades) << "sampled: the old action too, every faded frame";
  }
  ASSERT_GT(fades, 0u);
  EXPECT_LT(frozen_extra * 4, sampled_extra) << "frozen samples the old action once per change";
}

TEST(Transitions, ExactModesDrawFadingCopiesExactly) {
  CrowdBench bench(test::default_humanoid(), fading("threaded", Crossfade::Sampled));
  uint64_t fades = 0;
  for (int f = 0; f < 80; ++f) fades = bench.step().counters.fades;
  ASSERT_GT(fades, 0u);
  const DrawnErrorRecord error = bench.measure_drawn_error(900);
  EXPECT_GT(error.copies_checked, 0u);
  EXPECT_EQ(error.max, 0.0) << "the reference blends as the pose update does";
}

// No pop: between frames a fading copy's joints (their positions in model
// space, from the skinning matrices and the bind pose) move at most as far as
// its two actions' own moves plus the fade's share of the gap between them,
// plus 1e-4; the same bound fails when the change snaps (blend-in 0). The
// share is the straight gap over the fade's frames times kArc: joints blend
// by rotating, so they travel an arc, at most pi/2 times its chord (a half
// turn), and normalised lerp crosses the middle of a fade up to sqrt(2) times
// as fast as slerp (quaternions a half turn apart). On the humanoid a wave
// fading into a walk moves a hand 1.47 times its straight share at mid-fade.
double worst_pop(double bench_blend_in, double bound_blend_in) {
  BenchConfig config = fading("threaded", Crossfade::Sampled, 1, 6);
  config.mode.blend_in_s = bench_blend_in;
  config.mode.animation_culling = false;
  const Character& humanoid = test::default_humanoid();
  CrowdBench bench(humanoid, config);
  const Character* one[] = {&humanoid};
  TransitionSchedule schedule(one, bench.crowd(), {config.mode.transitions_s, bench_blend_in}, config.crowd.seed);
  const double fps = 60.0;
  const size_t joints = humanoid.skeleton.joint_count(), copies = bench.crowd().size();
  std::vector<std::vector<glm::vec3>> last(copies);
  ExactPalette scratch;
  std::vector<glm::vec4> bind_positions;
  for (const glm::mat4& inverse_bind : humanoid.skeleton.inverse_binds)
    bind_positions.push_back(glm::inverse(inverse_bind)[3]);
  auto origins = [&](std::span<const SkinMatrix> palette) {
    std::vector<glm::vec3> out;
    for (size_t j = 0; j < palette.size(); ++j) out.emplace_back(palette[j] * bind_positions[j]);
    return out;
  };
  auto action_at = [&](const ActionClock& clock, double t) {
    const Action& action = humanoid.actions[clock.action];
    return origins(scratch.at(humanoid.skeleton, &action, bind_action(humanoid.skeleton, action).targets,
                              clock.local_time(action, t)));
  };
  auto largest = [&](const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    double most = 0;
    for (size_t j = 0; j < joints; ++j) most = std::max(most, static_cast<double>(glm::distance(a[j], b[j])));
    return most;
  };
  double worst = -1e9;
  for (int f = 0; f < 240; ++f) {
    bench.step();
    const double t = f / fps;
    schedule.advance(t);
    for (size_t i = 0; i < copies; ++i) {
      std::vector<glm::vec3> now = origins(bench.skinning_matrices(i));
      const CopyAction& c = schedule[i];
      // Frames from the change until the fade the bound assumes is over.
      if (f > 0 && c.changes > 0 && c.changed_at > t - 1.0 / fps - bound_blend_in) {
        const double own = std::max(largest(action_at(c.before, t), action_at(c.before, t - 1 / fps)),
                                    largest(action_at(c.now, t), action_at(c.now, t - 1 / fps)));
        const double gap = largest(action_at(c.before, t), action_at(c.now, t));
        constexpr double kArc = 1.5707963 * 1.4142136;
        const double excess = largest(now, last[i]) - (own + kArc * gap / (bound_blend_in * fps) + 1e-4);
        worst = std::max(worst, excess);
      }
      last[i] = std::move(now);
    }
  }
  return worst;
}

TEST(Transitions, AFadeMovesNoJointFurtherThanItsActionsAndTheFadeAllow) {
  EXPECT_LE(worst_pop(0.4, 0.4), 0.0) << "a fade of 0.4 s within its bound";
  EXPECT_GT(worst_pop(0.0, 0.4), 0.0) << "a snap breaks the same bound";
}

// Sharing: copies whose actions, times and fade match share one evaluation;
// with exact times (no quantum) the shared crowd shows what every copy
// computed alone would, fading or not, and a group with shared actions fades
// as one evaluation.
TEST(Transitions, SharedPosesFadeAsTheCopiesAloneWould) {
  for (ActionChoice actions : {ActionChoice::Shared, ActionChoice::Random}) {
    BenchConfig alone_config = fading("threaded", Crossfade::Sampled),
                shared_config = fading("shared", Crossfade::Sampled);
    alone_config.crowd.actions = shared_config.crowd.actions = actions;
    shared_config.mode.share_quantum_s = 0.0;
    CrowdBench alone(test::default_humanoid(), alone_config), shared(test::default_humanoid(), shared_config);
    size_t fading_frames = 0;
    for (int f = 0; f < 150; ++f) {
      const Counters a = alone.step().counters, s = shared.step().counters;
      ASSERT_EQ(alone.digest(), shared.digest()) << "frame " << f;
      ASSERT_EQ(a.fades > 0, s.fades > 0) << "frame " << f;
      if (s.fades == 0) continue;
      ++fading_frames;
      if (actions == ActionChoice::Shared) EXPECT_EQ(s.poses_updated, 1u) << "one fade for the whole group";
    }
    EXPECT_GT(fading_frames, 10u);
  }
}

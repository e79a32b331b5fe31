// Issue 13: animation sharing, update-rate LOD and the animation budget. Their
// counters are exact, the deviation is checked against cases worked by hand,
// the budget's choices are pinned for a fixed sequence of times, and digests
// do not depend on the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "animation/pose_sharing.h"
#include "animation/update_rates.h"
#include "frame/run_bench.h"
#include "gen/humanoid.h"
#include "measuring/trace.h"
#include "reports/profile_table.h"
#include "result/result_codec.h"
#include "one_joint_character.h"
#include "test_support.h"
#include "characters.h"

using namespace crowdprof;

namespace {

using test::humanoid_glb;
using test::small_humanoid;

// One joint that slides along +X at 1 unit per second for one second, and a
// mesh 2 units tall bound rigidly to it: every vertex is displaced by exactly
// the joint's translation, so deviations can be worked out by hand.
const Character& slider() {
  static const Character character = test::one_joint_character(
      "slider", {{0, 0, 0}, {0, 2, 0}, {0.5f, 0, 0}, {0, 1, 0.5f}}, std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)),
      {0, 1, 2, 0, 2, 3}, ChannelPath::Translation, {0, 0, 0, 1, 0, 0});
  return character;
}

BenchConfig config_for(const std::string& mode, int threads, size_t copies, ActionChoice actions) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode_name = mode;
  config.threads = threads;
  config.crowd.copies = copies;
  config.crowd.actions = actions;
  config.crowd.seed = 3;
  return config;
}

FrameRecord last_of_frames(CrowdBench& bench, int frames) {
  FrameRecord last;
  for (int i = 0; i < frames; ++i) last = bench.step();
  return last;
}

}  // namespace

// --- the pieces, alone -------------------------------------------------------

TEST(PoseSharing, CopiesInOneStateShareOneStorage) {
  std::vector<uint16_t> kinds = {0, 0, 0, 1};
  PoseSharing sharing;
  sharing.reset(kinds, 2);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(sharing.shown(i), i);
  uint64_t a = state_key(0, 0, 100), b = state_key(0, 1, 100), c = state_key(1, 0, 100);
  for (size_t i = 0; i < 4; ++i) sharing.release(i);
  bool evaluate = false;
  uint32_t first = sharing.take(0, a, &evaluate);
  EXPECT_TRUE(evaluate);
  EXPECT_EQ(sharing.take(1, a, &evaluate), first);
  EXPECT_FALSE(evaluate);
  EXPECT_EQ(sharing.viewers(first), 2u);
  uint32_t other = sharing.take(2, b, &evaluate);
  EXPECT_TRUE(evaluate);
  EXPECT_NE(other, first);
  EXPECT_LT(other, 3u);                          // a storage of the same character
  EXPECT_EQ(sharing.take(3, c, &evaluate), 3u);  // the only storage of character 1
  EXPECT_TRUE(evaluate);

  // Copy 2 leaves state b and copy 0 leaves a: b's storage keeps b until room
  // is needed, so copy 0 taking b again evaluates nothing.
  sharing.release(2);
  sharing.release(0);
  EXPECT_EQ(sharing.take(0, b, &evaluate), other);
  EXPECT_FALSE(evaluate);
  // A new state takes the storage released longest ago that no copy shows.
  uint32_t fresh = sharing.take(2, state_key(0, 0, 200), &evaluate);
  EXPECT_TRUE(evaluate);
  EXPECT_NE(fresh, first);  // copy 1 still shows a
  EXPECT_NE(fresh, other);  // copy 0 shows b
  EXPECT_EQ(sharing.key_of(first), a);
}

TEST(PoseSharing, TheStorageTakenLastIsTakenBackFromTheFreeList) {
  // take() answers a key equal to the last one taken without hashing; when no
  // copy shows that storage any more it is on the free list, and taking it
  // back must take it off, or a new state could overwrite it.
  std::vector<uint16_t> kinds = {0, 0};
  PoseSharing sharing;
  sharing.reset(kinds, 1);
  sharing.release(0);
  sharing.release(1);
  bool evaluate = false;
  uint64_t a = state_key(0, 0, 1), c = state_key(0, 0, 2), d = state_key(0, 0, 3);
  uint32_t t = sharing.take(1, c, &evaluate);
  uint32_t s = sharing.take(0, a, &evaluate);
  ASSERT_NE(s, t);
  sharing.release(0);  // s holds a, no copy shows it: free
  EXPECT_EQ(sharing.take(0, a, &evaluate), s);
  EXPECT_FALSE(evaluate);
  sharing.release(1);  // t is the only free storage now
  EXPECT_EQ(sharing.take(1, d, &evaluate), t);
  EXPECT_TRUE(evaluate);
  EXPECT_EQ(sharing.key_of(sharing.shown(0)), a);
  EXPECT_EQ(sharing.viewers(s), 1u);
}

TEST(PoseSharing, ManyCopiesAtOnceAsOneByOne) {
  // The frame loop releases and takes runs of copies at once; the storages
  // each copy shows, their keys and viewers are those of one call a copy.
  std::vector<uint16_t> kinds(40, 0);
  PoseSharing one, many;
  one.reset(kinds, 1);
  many.reset(kinds, 1);
  for (uint32_t frame = 0; frame < 30; ++frame) {
    std::vector<uint32_t> copies;
    std::vector<uint64_t> keys;
    for (uint32_t i = 0; i < 40; ++i) {
      if ((i + frame) % 7 == 3) continue;  // some copies keep their state
      copies.push_back(i);
      // Runs of equal keys of several lengths, states coming back now and then.
      keys.push_back(state_key(0, 0, (frame + i / (1 + frame % 5)) % 11));
    }
    for (uint32_t c : copies) one.release(c);
    many.release(copies);
    std::vector<uint32_t> evaluated_one, evaluated_many;
    for (size_t c = 0; c < copies.size(); ++c) {
      bool evaluate = false;
      uint32_t s = one.take(copies[c], keys[c], &evaluate);
      if (evaluate) evaluated_one.push_back(s);
    }
    for (size_t c = 0; c < copies.size();) {
      size_t end = c + 1;
      while (end < copies.size() && keys[end] == keys[c]) ++end;
      bool evaluate = false;
      uint32_t s = many.take(std::span(copies).subspan(c, end - c), keys[c], &evaluate);
      if (evaluate) evaluated_many.push_back(s);
      c = end;
    }
    ASSERT_EQ(evaluated_one, evaluated_many) << frame;
    for (uint32_t i = 0; i < 40; ++i) {
      ASSERT_EQ(one.shown(i), many.shown(i)) << frame << " " << i;
      ASSERT_EQ(one.viewers(i), many.viewers(i)) << frame << " " << i;
      ASSERT_EQ(one.key_of(i), many.key_of(i)) << frame << " " << i;
    }
  }
}

TEST(PoseSharing, ManyStatesComeAndGoWithoutLosingOne) {
  // 64 copies of one character walk through states; a copy's storage always
  // holds the key it asked for.
  std::vector<uint16_t> kinds(64, 0);
  PoseSharing sharing;
  sharing.reset(kinds, 1);
  for (uint32_t frame = 0; frame < 50; ++frame) {
    for (size_t i = 0; i < 64; ++i) sharing.release(i);
    for (size_t i = 0; i < 64; ++i) {
      bool evaluate = false;
      uint64_t key = state_key(0, static_cast<uint16_t>(i % 5), (frame + static_cast<uint32_t>(i) * 7) % 23);
      uint32_t s = sharing.take(i, key, &evaluate);
      ASSERT_EQ(sharing.key_of(s), key);
    }
  }
}

TEST(UpdateRates, LodShiftByThresholds) {
  EXPECT_EQ(lod_shift(0.30f, 0.25f, 0.125f, 0.0625f), 0);
  EXPECT_EQ(lod_shift(0.25f, 0.25f, 0.125f, 0.0625f), 0);
  EXPECT_EQ(lod_shift(0.20f, 0.25f, 0.125f, 0.0625f), 1);
  EXPECT_EQ(lod_shift(0.10f, 0.25f, 0.125f, 0.0625f), 2);
  EXPECT_EQ(lod_shift(0.01f, 0.25f, 0.125f, 0.0625f), 3);
}

TEST(UpdateRates, DueOnItsTurnAndNeverLaterThanItsPeriod) {
  EXPECT_TRUE(update_due(5, -1, 3, 0));  // never updated
  EXPECT_TRUE(update_due(8, 4, 3, 0));   // its turn: 8 + 0 is a multiple of 8
  EXPECT_FALSE(update_due(9, 8, 3, 0));
  EXPECT_TRUE(update_due(7, 6, 3, 1));     // 7 + 1
  EXPECT_TRUE(update_due(20, 12, 3, 5));   // not its turn, but 8 frames since the last
  EXPECT_FALSE(update_due(18, 12, 3, 5));  // 18 + 5 is not a multiple of 8, 6 frames since
}

TEST(AnimBudget, ChoicesPinnedForAFixedSequenceOfTimes) {
  // Four copies, 0.4, 0.1, 0.3 and 0.05 of the screen: the budget slows
  // copy 3, then 1, then 2, then 0, round after round.
  std::vector<float> screen = {0.4f, 0.1f, 0.3f, 0.05f};
  std::vector<uint8_t> base = {0, 0, 0, 0}, eligible = {1, 1, 1, 1};
  BudgetPlan plan = make_budget_plan(screen, base, eligible);
  ASSERT_EQ(plan.order, (std::vector<uint32_t>{3, 1, 2, 0}));
  EXPECT_EQ(plan.expected_updates(0), 4.0);
  EXPECT_EQ(plan.expected_updates(1), 3.5);
  EXPECT_EQ(plan.expected_updates(4), 2.0);
  EXPECT_EQ(plan.expected_updates(6), 1.5);
  EXPECT_EQ(plan.expected_updates(plan.max_demotions()), 4.0 / 64);
  EXPECT_EQ(plan.demoted_shift(0, 6), 2);  // copy 3: two rounds
  EXPECT_EQ(plan.demoted_shift(2, 6), 1);  // copy 2: one
  EXPECT_EQ(plan.demoted_shift(3, 100), kMaxRateShift);

  // (measured ms, updates done) -> doublings, budget 2 ms aimed at 1.5 ms.
  struct Step {
    double ms;
    uint64_t updates;
    uint64_t expect;
  };
  // 4 ms for 4 updates: 1 ms each, so 1.5 updates fit: 6 doublings.
  // 1 ms for 2 updates: 0.5 each, 3 fit: 2 doublings. Nothing done: kept.
  // 100 ms for 4: not even every copy every 64 frames fits: all at 64.
  // 0.1 ms for 1 update: 15 fit, more than 4 copies: none slowed.
  const Step steps[] = {{4.0, 4, 6}, {1.0, 2, 2}, {0.0, 2, 2}, {3.0, 0, 2}, {100.0, 4, 24}, {0.1, 1, 0}};
  uint64_t demotions = 0;
  for (const Step& step : steps) {
    AnimBudgetJob job{&plan, 2.0, step.ms, step.updates, &demotions};
    ASSERT_TRUE(job.Run());
    EXPECT_EQ(demotions, step.expect) << step.ms << " ms, " << step.updates << " updates";
  }
  EXPECT_FALSE((AnimBudgetJob{&plan, 0.0, 1.0, 1, &demotions}.Run()));
  EXPECT_FALSE((AnimBudgetJob{nullptr, 2.0, 1.0, 1, &demotions}.Run()));
}

TEST(AnimBudget, LodShiftsStayAndOnlyEligibleCopiesEnter) {
  std::vector<float> screen = {0.4f, 0.1f, 0.3f};
  std::vector<uint8_t> base = {0, 2, 1}, eligible = {1, 0, 1};
  BudgetPlan plan = make_budget_plan(screen, base, eligible);
  ASSERT_EQ(plan.order, (std::vector<uint32_t>{2, 0}));
  EXPECT_EQ(plan.expected_updates(0), 1.5);  // copy 2 every 2nd frame, copy 0 every frame
  EXPECT_EQ(plan.demoted_shift(0, 1), 2);
  EXPECT_EQ(plan.expected_updates(1), 1.25);
}

// --- in the frame loop ----------------------------------------------------------

TEST(CrowdScale, SharedActionIsOnePoseAndOneMeshAFrame) {
  const Character& character = small_humanoid();
  CrowdBench threaded(character, config_for("threaded", 2, 160, ActionChoice::Shared));
  CrowdBench shared(character, config_for("shared", 2, 160, ActionChoice::Shared));
  FrameRecord a, b;
  for (int frame = 0; frame < 5; ++frame) {
    a = threaded.step();
    b = shared.step();
    EXPECT_EQ(b.counters.poses_updated, 1u) << frame;
    EXPECT_EQ(b.counters.vertices_skinned, character.mesh.vertex_count()) << frame;
    EXPECT_EQ(b.counters.copies_updated, a.counters.poses_updated) << frame;
    EXPECT_EQ(b.counters.updates_every_1, a.counters.poses_updated) << frame;
    EXPECT_EQ(b.counters.copies_held, 0u);
    EXPECT_EQ(b.counters.copies_visible, a.counters.copies_visible);
    EXPECT_EQ(b.counters.copies_culled, a.counters.copies_culled);
  }
  EXPECT_EQ(a.counters.copies_updated, a.counters.poses_updated);  // without sharing, one pose per copy
  // Exact times: every copy draws what threaded draws, so the digest is the same.
  EXPECT_EQ(shared.digest(), threaded.digest());
  size_t storage = SIZE_MAX;
  for (size_t i = 0; i < shared.crowd().size(); ++i) {
    if (!shared.visible(i)) continue;
    if (storage == SIZE_MAX) storage = shared.storage_of(i);
    EXPECT_EQ(shared.storage_of(i), storage);  // one mesh, drawn by every copy on screen
  }
  AnimationRecord fidelity = shared.measure_animation();
  EXPECT_EQ(fidelity.max_deviation, 0.0);
  EXPECT_EQ(fidelity.copies_deviating, 0u);
  EXPECT_EQ(fidelity.copies_checked, a.counters.copies_visible);
}

TEST(CrowdScale, FewerStatesThanThreadsAreSkinnedInParts) {
  // One state a frame on 3 threads: its mesh is skinned in 4 parts a thread,
  // each a task of its own, with the same bits as on one thread (where the
  // state is one task, posed and skinned), in both vertex formats.
  const Character& character = small_humanoid();
  for (VertexFormat format : {VertexFormat::Float, VertexFormat::Packed}) {
    std::string digest[2];
    for (int threads : {1, 3}) {
      Tracer tracer;
      BenchConfig config = config_for("shared", threads, 40, ActionChoice::Shared);
      config.mode.vertex_format = format;
      config.tracer = &tracer;
      CrowdBench bench(character, config);
      FrameRecord last = last_of_frames(bench, 3);
      EXPECT_EQ(last.counters.poses_updated, 1u);
      EXPECT_EQ(last.counters.vertices_skinned, character.mesh.vertex_count());
      std::map<std::string, size_t> tasks;
      for (const TraceSpan& span : tracer.spans())
        if (span.category == "task") ++tasks[std::string(span.name)];
      if (threads == 1)
        EXPECT_EQ(tasks, (std::map<std::string, size_t>{{"pose+skin", 3}}));
      else
        EXPECT_EQ(tasks, (std::map<std::string, size_t>{{"pose+skin part", 3 * 12}}));
      digest[threads == 1 ? 0 : 1] = bench.digest();
    }
    EXPECT_EQ(digest[0], digest[1]) << (format == VertexFormat::Packed ? "packed" : "float");
  }
  // As many states as threads or more: one task per state, as in threaded.
  Tracer tracer;
  BenchConfig config = config_for("shared", 2, 40, ActionChoice::Random);
  config.mode.animation_culling = false;
  config.tracer = &tracer;
  CrowdBench bench(character, config);
  FrameRecord first = bench.step();
  ASSERT_GE(first.counters.poses_updated, 2u);
  size_t tasks = 0;
  for (const TraceSpan& span : tracer.spans())
    if (span.category == "task") tasks += span.name == "pose+skin";
  EXPECT_EQ(tasks, first.counters.poses_updated);
}

TEST(CrowdScale, QuantumGroupsRandomCopiesIntoDistinctStates) {
  const Character& character = small_humanoid();
  BenchConfig config = config_for("shared", 1, 96, ActionChoice::Random);
  config.mode.share_quantum_s = 0.25;
  config.mode.animation_culling = false;
  CrowdBench bench(character, config);
  FrameRecord first = bench.step();
  // Worked out apart from the bench: the states of frame 0 are the distinct
  // (action, time snapped to 0.25 s) of the copies.
  std::set<std::pair<int, float>> states;
  const Crowd& crowd = bench.crowd();
  for (size_t i = 0; i < crowd.size(); ++i) {
    const Action& action = character.actions[crowd.action[i]];
    float local = action.start + static_cast<float>(std::fmod(static_cast<double>(crowd.phase[i]), action.duration()));
    float snapped =
        std::min(action.end, action.start + static_cast<float>(std::nearbyint((local - action.start) / 0.25) * 0.25));
    states.insert({crowd.action[i], snapped});
  }
  EXPECT_EQ(first.counters.poses_updated, states.size());
  EXPECT_LT(first.counters.poses_updated, 96u);
  EXPECT_EQ(first.counters.copies_updated, 96u);
  EXPECT_EQ(first.counters.vertices_skinned, states.size() * character.mesh.vertex_count());
  // Copies in one state draw one storage.
  std::set<size_t> storages;
  for (size_t i = 0; i < crowd.size(); ++i) storages.insert(bench.storage_of(i));
  EXPECT_EQ(storages.size(), states.size());
}

TEST(CrowdScale, DeviationOfAQuantumWorkedByHand) {
  // fps 10: frame 3 shows t = 0.3 s; a 0.4 s quantum snaps it to 0.4 s. The
  // slider moves 1 unit a second: every vertex is 0.1 off, 0.05 of its 2 units.
  BenchConfig config = config_for("shared", 1, 1, ActionChoice::Shared);
  config.fps = 10;
  config.mode.share_quantum_s = 0.4;
  CrowdBench bench(slider(), config);
  last_of_frames(bench, 4);
  AnimationRecord fidelity = bench.measure_animation();
  EXPECT_EQ(fidelity.copies_checked, 1u);
  EXPECT_EQ(fidelity.copies_deviating, 1u);
  EXPECT_NEAR(fidelity.max_deviation, 0.1, 1e-6);
  EXPECT_NEAR(fidelity.deviation_fraction_of_height, 0.05, 1e-6);
  // Frame 4 shows t = 0.4 s: exact again.
  bench.step();
  EXPECT_EQ(bench.measure_animation().max_deviation, 0.0);
}

TEST(CrowdScale, UpdateRateLodHoldsAndCountsByHand) {
  // Thresholds no copy reaches but the last: every copy is updated every 2nd
  // frame. fps 4: frame 3 shows t = 0.75 s, but the copy was last updated on
  // frame 2 (t = 0.5 s) and holds it: 0.25 off, 0.125 of its height.
  BenchConfig config = config_for("threaded", 1, 1, ActionChoice::Shared);
  config.fps = 4;
  config.mode.update_lod = true;
  config.mode.lod = {2.0f, 0.0f, 0.0f};
  CrowdBench bench(slider(), config);
  FrameRecord frames[4];
  for (FrameRecord& f : frames) f = bench.step();
  uint64_t updated[4] = {1, 0, 1, 0};
  for (int f = 0; f < 4; ++f) {
    EXPECT_EQ(frames[f].counters.copies_updated, updated[f]) << f;
    EXPECT_EQ(frames[f].counters.updates_every_2, updated[f]) << f;
    EXPECT_EQ(frames[f].counters.poses_updated, updated[f]) << f;
    EXPECT_EQ(frames[f].counters.copies_held, 1 - updated[f]) << f;
  }
  AnimationRecord fidelity = bench.measure_animation();
  EXPECT_NEAR(fidelity.max_deviation, 0.25, 1e-6);
  EXPECT_NEAR(fidelity.deviation_fraction_of_height, 0.125, 1e-6);
  EXPECT_EQ(bench.schedule().longest_gap, 2u);
  EXPECT_EQ(bench.schedule().copies_by_rate[1], 1u);
}

TEST(CrowdScale, LodCopiesTakeTurns) {
  // Every copy every 2nd frame: after the first frame, odd and even copies
  // alternate, so each frame updates half of them.
  BenchConfig config = config_for("threaded", 2, 24, ActionChoice::Random);
  config.mode.update_lod = true;
  config.mode.animation_culling = false;
  config.mode.lod = {2.0f, 0.0f, 0.0f};
  CrowdBench bench(small_humanoid(), config);
  EXPECT_EQ(bench.step().counters.copies_updated, 24u);
  for (int frame = 1; frame < 6; ++frame) {
    FrameRecord r = bench.step();
    EXPECT_EQ(r.counters.copies_updated, 12u) << frame;
    EXPECT_EQ(r.counters.updates_every_2, 12u) << frame;
    EXPECT_EQ(r.counters.copies_held, 12u) << frame;
  }
  EXPECT_EQ(bench.schedule().longest_gap, 2u);
}

TEST(CrowdScale, BudgetNeverStarvesACopy) {
  // Replayed times far over the budget: every copy falls to every 64th frame,
  // and none waits longer than that.
  BenchConfig config = config_for("threaded", 1, 24, ActionChoice::Random);
  config.mode.anim_budget_ms = 1.0;
  config.mode.animation_culling = false;
  config.replay_animations_ms = {1000.0};
  CrowdBench bench(small_humanoid(), config);
  uint64_t updates = 0;
  for (int frame = 0; frame < 130; ++frame) {
    FrameRecord r = bench.step();
    if (frame > 0) {
      updates += r.counters.copies_updated;
      EXPECT_LE(r.counters.copies_updated, 1u) << frame;  // 24 copies take turns over 64 frames
      EXPECT_EQ(r.counters.copies_updated, r.counters.updates_every_64) << frame;
    }
  }
  EXPECT_EQ(bench.schedule().copies_by_rate[kMaxRateShift], 24u);
  EXPECT_EQ(bench.schedule().longest_gap, 64u);
  EXPECT_GE(updates, 48u);  // each copy at least twice in 129 frames
}

TEST(CrowdScale, DigestsDoNotDependOnThreads) {
  struct Case {
    const char* name;
    ActionChoice actions;
    double quantum;
    bool lod;
    double budget;
  };
  const Case cases[] = {{"shared", ActionChoice::Shared, 0, false, 0},
                        {"shared quantum", ActionChoice::Random, 1.0 / 30, false, 0},
                        {"lod", ActionChoice::Random, 0, true, 0},
                        {"budget", ActionChoice::Random, 1.0 / 30, true, 0.5}};
  for (const Case& c : cases) {
    std::string reference;
    for (int threads : {1, 2, 5}) {
      BenchConfig config = config_for("shared", threads, 48, c.actions);
      config.mode.share_quantum_s = c.quantum;
      config.mode.update_lod = c.lod;
      config.mode.lod = {0.5f, 0.3f, 0.2f};  // a spread of rates at this crowd size
      config.mode.anim_budget_ms = c.budget;
      config.replay_animations_ms = {0.2, 0.9, 0.4, 1.5, 0.1};
      CrowdBench bench(small_humanoid(), config);
      last_of_frames(bench, 12);
      if (reference.empty()) reference = bench.digest();
      EXPECT_EQ(bench.digest(), reference) << c.name << " on " << threads << " threads";
    }
  }
}

TEST(CrowdScale, HeldPosesChangeTheDigest) {
  // The digest describes what is drawn: a held pose is not the exact one.
  BenchConfig exact = config_for("threaded", 1, 24, ActionChoice::Random);
  BenchConfig held = exact;
  held.mode.update_lod = true;
  held.mode.lod = {2.0f, 0.0f, 0.0f};
  CrowdBench a(small_humanoid(), exact), b(small_humanoid(), held);
  last_of_frames(a, 4);
  last_of_frames(b, 4);
  EXPECT_NE(a.digest(), b.digest());
}

TEST(CrowdScale, RunReportsTheSchedule) {
  BenchConfig config = config_for("budget", 1, 24, ActionChoice::Random);
  config.replay_animations_ms = {0.5};
  CrowdBench bench(small_humanoid(), config);
  RunOptions options;
  options.frames = 6;
  options.warmup = 2;
  Result report = run_bench(bench, "humanoid", options);
  ASSERT_TRUE(report.animation.has_value());
  EXPECT_EQ(report.animation->copies_by_rate.size(), kRateCount);
  nlohmann::json j = result_to_json(report);
  EXPECT_EQ(j["switches"]["share"], true);
  EXPECT_EQ(j["switches"]["anim_budget"], 2.0);
  EXPECT_TRUE(j.contains("animation"));
  EXPECT_NE(format_profile(report).find("longest gap"), std::string::npos);
  // Modes without issue 13's switches report nothing new.
  CrowdBench plain(small_humanoid(), config_for("threaded", 1, 24, ActionChoice::Random));
  Result plain_report = run_bench(plain, "humanoid", options);
  EXPECT_FALSE(plain_report.animation.has_value());
  EXPECT_FALSE(result_to_json(plain_report)["switches"].contains("share"));
}

// --- from the command line ------------------------------------------------------

TEST(CrowdScaleCli, SharedPresetOnTheThesisScene) {
  auto dir = crowdprof::test::scratch_dir("crowd_scale_cli");
  auto json_path = (dir / "shared.json").string();
  auto r = crowdprof::test::run_cli("bench '" + humanoid_glb() +
                                    "' -n 40 --mode shared --frames 2 --warmup 0 -q --json '" + json_path + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(json_path);
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["mode"], "shared");
  EXPECT_EQ(j["counters"]["poses_updated"], 1);
  EXPECT_EQ(j["counters"]["vertices_skinned"], j["scene"]["vertices"]);
  EXPECT_EQ(j["counters"]["copies_updated"], j["counters"]["copies_visible"]);
  EXPECT_EQ(j["animation"]["max_deviation"], 0.0);
  // A switch away from the preset makes the mode custom and is recorded.
  r = crowdprof::test::run_cli("bench '" + humanoid_glb() +
                               "' -n 40 --actions random --mode shared --share-quantum 1/30 --update-lod on "
                               "--lod-thresholds 0.5,0.2,0.1 --frames 2 --warmup 0 -q --json '" +
                               json_path + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream again(json_path);
  j = nlohmann::json::parse(again);
  EXPECT_EQ(j["mode"], "shared+custom");
  EXPECT_DOUBLE_EQ(j["switches"]["share_quantum"].get<double>(), 1.0 / 30);
  EXPECT_EQ(j["switches"]["lod_thresholds"], "0.5,0.2,0.1");
  EXPECT_LT(j["counters"]["poses_updated"].get<int>(), j["counters"]["copies_updated"].get<int>());
}

TEST(CrowdScaleCli, BadValuesAreUsageErrors) {
  struct Bad {
    const char* args;
    const char* words;
  };
  for (const Bad& bad :
       {Bad{"--share maybe", "--share"}, Bad{"--share-quantum soon", "--share-quantum"},
        Bad{"--mode shared --share-quantum -1", "--share-quantum"},
        Bad{"--mode shared --share-quantum 1/0", "--share-quantum"}, Bad{"--share-quantum 1/30", "needs --share on"},
        Bad{"--update-lod yes", "--update-lod"}, Bad{"--lod-thresholds 0.1,0.2,0.3", "--lod-thresholds"},
        Bad{"--lod-thresholds 0.5,0.2", "--lod-thresholds"}, Bad{"--anim-budget -2", "--anim-budget"},
        Bad{"--anim-budget 2ms", "--anim-budget"}}) {
    auto r = crowdprof::test::run_cli("bench '" + humanoid_glb() + "' -n 4 --frames 1 --warmup 0 " + bad.args);
    EXPECT_EQ(r.status, 2) << bad.args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(bad.words), std::string::npos) << bad.args << ": " << r.err;
  }
}

TEST(CrowdScaleCli, WithAGlBackendOneSharedMeshIsUploadedOnce) {
  if (!crowdprof::test::have_gl()) GTEST_SKIP() << "no GL here";
  auto dir = crowdprof::test::scratch_dir("crowd_scale_gl");
  nlohmann::json runs[2];
  const char* modes[2] = {"threaded", "shared"};
  for (int m = 0; m < 2; ++m) {
    auto json_path = (dir / (std::string(modes[m]) + ".json")).string();
    auto r = crowdprof::test::run_cli("bench '" + humanoid_glb() + "' -n 12 --mode " + modes[m] +
                                      " --backend auto --resolution 320x180 --frames 2 --warmup 0 -q --json '" +
                                      json_path + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(json_path);
    runs[m] = nlohmann::json::parse(in);
  }
  const nlohmann::json &threaded = runs[0]["counters"], &shared = runs[1]["counters"];
  ASSERT_GT(threaded["copies_visible"].get<uint64_t>(), 1u);
  EXPECT_EQ(shared["draw_calls"], threaded["draw_calls"]);  // every copy drawn, with its own transform
  EXPECT_EQ(shared["bytes_uploaded"].get<uint64_t>() * threaded["copies_visible"].get<uint64_t>(),
            threaded["bytes_uploaded"].get<uint64_t>());  // one mesh uploaded, not one per copy
  EXPECT_EQ(runs[0]["digest"], runs[1]["digest"]);
}

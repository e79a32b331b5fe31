// The frame's jobs on their own, without a bench: the update plan (who is
// posed, shared, held) and the pose updates it feeds.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <memory>
#include <vector>

#include "characters.h"
#include "frame/copy_store.h"
#include "frame/pose_update.h"
#include "frame/prepared_character.h"
#include "frame/update_plan.h"
#include "scene/crowd.h"

namespace crowdprof {
namespace {

struct Plan {
  explicit Plan(const ModeSwitches& switches, size_t copies = 12, ActionChoice actions = ActionChoice::Shared)
      : mode(switches) {
    CrowdOptions options;
    options.copies = copies;
    options.actions = actions;
    crowd = make_crowd(characters, options);
    prepared = prepare_characters(characters, crowd.character_boxes, mode, 0, kind_layers(characters.size(), {}, mode));
    times.assign(copies, characters[0]->actions[0].start);
    for (size_t i = 0; i < copies; ++i)
      if (!crowd.phase.empty()) times[i] += crowd.phase[i];
    visible.assign(copies, 1);
    planner = std::make_unique<UpdatePlanner>(characters, crowd, glm::mat4(1.0f), mode, std::vector<uint8_t>{1});
  }
  std::span<const StateJob> run(uint64_t frame, Counters& counters) {
    return planner->plan({frame, times, visible, 0.0}, counters);
  }
  std::array<const Character*, 1> characters{&test::small_humanoid()};
  ModeSwitches mode;
  Crowd crowd;
  std::vector<PreparedCharacter> prepared;
  std::vector<float> times;
  std::vector<uint8_t> visible;
  std::unique_ptr<UpdatePlanner> planner;
};

TEST(UpdatePlan, EveryVisibleCopyIsOneEvaluationIntoItsOwnStorage) {
  Plan plan(find_mode("threaded")->switches);
  Counters counters;
  std::span<const StateJob> jobs = plan.run(0, counters);
  ASSERT_EQ(jobs.size(), 12u);
  for (size_t j = 0; j < jobs.size(); ++j) {
    EXPECT_EQ(jobs[j].leader, j);
    EXPECT_EQ(jobs[j].storage, j);
  }
  EXPECT_EQ(counters.copies_updated, 12u);
  EXPECT_EQ(counters.copies_held, 0u);
}

TEST(UpdatePlan, CullingLeavesCopiesOffScreenOut) {
  Plan plan(find_mode("culled")->switches);
  for (size_t i = 0; i < plan.visible.size(); i += 2) plan.visible[i] = 0;
  Counters counters;
  std::span<const StateJob> jobs = plan.run(0, counters);
  ASSERT_EQ(jobs.size(), 6u);
  for (const StateJob& job : jobs) EXPECT_EQ(job.leader % 2, 1u);
  EXPECT_FALSE(plan.planner->poses(0, plan.visible));
  EXPECT_TRUE(plan.planner->poses(1, plan.visible));
}

TEST(UpdatePlan, SharingEvaluatesEachStateOnceAndHoldsItAfterwards) {
  // One shared action, every copy at the same time: one state.
  Plan plan(find_mode("shared")->switches);
  Counters first;
  std::span<const StateJob> jobs = plan.run(0, first);
  ASSERT_EQ(jobs.size(), 1u);
  for (size_t i = 0; i < plan.times.size(); ++i) EXPECT_EQ(plan.planner->storage_of(i), jobs[0].storage);
  EXPECT_EQ(plan.planner->shown().size(), plan.times.size());
  // The same time next frame: the state is still shown, nothing to evaluate.
  Counters second;
  EXPECT_TRUE(plan.run(1, second).empty());
  // A new time: one evaluation again.
  for (float& t : plan.times) t += 0.1f;
  Counters third;
  EXPECT_EQ(plan.run(2, third).size(), 1u);
}

TEST(UpdatePlan, HalfRateCopiesTakeTurns) {
  ModeSwitches mode = find_mode("threaded")->switches;
  mode.update_lod = true;
  mode.lod = {2.0f, 0.0f, 0.0f};  // nothing fills two screens: every copy every 2nd frame
  Plan plan(mode);
  Counters counters;
  EXPECT_EQ(plan.run(0, counters).size(), 12u);  // the first frame poses everyone
  for (uint64_t frame = 1; frame < 5; ++frame) {
    Counters c;
    EXPECT_EQ(plan.run(frame, c).size(), 6u) << "frame " << frame;
    EXPECT_EQ(c.copies_held, 6u);
    EXPECT_EQ(c.updates_every_2, 6u);
  }
  EXPECT_EQ(plan.planner->schedule().longest_gap, 2u);
}

TEST(PoseUpdate, ThreadsWriteWhatOneThreadWrites) {
  // Random actions and phases: every copy its own pose.
  auto palettes = [](bool parallel) {
    ModeSwitches mode = find_mode("threaded")->switches;
    mode.parallel = parallel;
    Plan plan(mode, 12, ActionChoice::Random);
    CopyStore store(plan.characters, plan.prepared, plan.crowd, mode);
    store.visible.assign(store.visible.size(), 1);
    for (size_t i = 0; i < store.times.size(); ++i) {
      const Action& action = plan.characters[0]->actions[plan.crowd.action[i]];
      store.times[i] = action.start + plan.crowd.phase[i];
    }
    PoseUpdater updater({plan.characters, plan.prepared, &plan.crowd, &store, mode, 2, nullptr, 1, {}});
    Counters counters;
    std::span<const StateJob> jobs = plan.planner->plan({0, store.times, store.visible, 0.0}, counters);
    EXPECT_EQ(jobs.size(), 12u);
    EXPECT_EQ(updater.update(jobs), 0u);  // bundled lookups: no string lookups
    return std::vector<SkinMatrix>(store.palettes.begin(), store.palettes.end());
  };
  std::vector<SkinMatrix> serial = palettes(false), parallel = palettes(true);
  ASSERT_EQ(serial.size(), parallel.size());
  // Posed, not left at rest: copies in different poses have different palettes.
  const size_t joints = test::small_humanoid().skeleton.joint_count();
  EXPECT_NE(std::memcmp(serial.data(), serial.data() + joints, joints * sizeof(SkinMatrix)), 0);
  EXPECT_EQ(std::memcmp(serial.data(), parallel.data(), serial.size() * sizeof(SkinMatrix)), 0);
}

TEST(PoseUpdate, PerFrameStringLookupsAreCounted) {
  ModeSwitches mode = find_mode("master")->switches;
  Plan plan(mode, 4);
  CopyStore store(plan.characters, plan.prepared, plan.crowd, mode);
  store.times = plan.times;
  store.visible.assign(store.visible.size(), 1);
  PoseUpdater updater({plan.characters, plan.prepared, &plan.crowd, &store, mode, 1, nullptr, 1, {}});
  Counters counters;
  const size_t channels = plan.characters[0]->actions[0].channels.size();
  EXPECT_EQ(updater.update(plan.planner->plan({0, store.times, store.visible, 0.0}, counters)), 4 * channels);
}

}  // namespace
}  // namespace crowdprof

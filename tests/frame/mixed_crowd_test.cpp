// Mixed crowds in the library: copies of several characters share a frame
// loop; the modes and thread counts agree bit for bit, counters add up per
// character, weighted actions pick only what has weight, and the camera is
// Blender's.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

#include "frame/crowd_bench.h"
#include "gen/humanoid.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

const std::vector<const Character*>& characters() {
  static const Character a = generate_humanoid({30, 800, 7});
  static const Character b = generate_humanoid({45, 600, 8});
  static const Character c = generate_humanoid({20, 500, 9});
  static const std::vector<const Character*> all = {&a, &b, &c};
  return all;
}

BenchConfig mixed(const std::string& mode, int threads) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode_name = mode;
  config.threads = threads;
  config.crowd.copies = 30;
  config.crowd.seed = 4;
  config.crowd.groups = {{0, 10, ActionChoice::Random, 0, {}},
                         {1, 12, ActionChoice::Shared, 1, {}},
                         {2, 8, ActionChoice::Weighted, 0, {0.0, 2.0, 1.0}}};
  return config;
}

}  // namespace

TEST(MixedCrowd, ModesAndThreadCountsAgreeBitForBit) {
  CrowdBench reference(characters(), mixed("master", 1));
  for (int i = 0; i < 4; ++i) reference.step();
  for (auto [mode, threads] : {std::pair{"culled", 1}, {"threaded", 1}, {"threaded", 2}, {"threaded", 5}}) {
    CrowdBench other(characters(), mixed(mode, threads));
    for (int i = 0; i < 4; ++i) other.step();
    EXPECT_EQ(reference.digest(), other.digest()) << mode << " " << threads;
  }
}

TEST(MixedCrowd, CountersAddUpPerCharacter) {
  BenchConfig config = mixed("culled", 1);
  CrowdBench bench(characters(), config);
  FrameRecord r = bench.step();
  ASSERT_EQ(bench.character_counters().size(), 3u);
  std::vector<size_t> copies(3, 0);
  for (size_t i = 0; i < bench.crowd().size(); ++i) ++copies[bench.crowd().kind[i]];
  EXPECT_EQ(copies, (std::vector<size_t>{10, 12, 8}));
  uint64_t poses = 0, culled = 0, skinned = 0, visible = 0;
  for (size_t k = 0; k < 3; ++k) {
    const Counters& c = bench.character_counters()[k];
    EXPECT_EQ(c.poses_updated + c.copies_culled, copies[k]);
    EXPECT_EQ(c.vertices_skinned, c.poses_updated * characters()[k]->mesh.vertex_count());
    poses += c.poses_updated, culled += c.copies_culled, skinned += c.vertices_skinned, visible += c.copies_visible;
  }
  EXPECT_EQ(poses, r.counters.poses_updated);
  EXPECT_EQ(culled, r.counters.copies_culled);
  EXPECT_EQ(skinned, r.counters.vertices_skinned);
  EXPECT_EQ(visible, r.counters.copies_visible);
  // Each copy's buffers are its own character's size.
  for (size_t i = 0; i < bench.crowd().size(); ++i) {
    EXPECT_EQ(bench.skinned_positions(i).size(), bench.character_of(i).mesh.vertex_count());
    EXPECT_EQ(bench.skinning_matrices(i).size(), bench.character_of(i).skeleton.joint_count());
  }
}

TEST(MixedCrowd, WeightedActionsPickOnlyWhatHasWeight) {
  CrowdOptions options;
  options.copies = 200;
  options.groups = {{0, 200, ActionChoice::Weighted, 0, {0.0, 3.0, 1.0}}};
  Crowd crowd = make_crowd(characters(), options);
  std::vector<size_t> count(3, 0);
  for (uint16_t a : crowd.action) ++count[a];
  EXPECT_EQ(count[0], 0u);
  EXPECT_GT(count[1], 2 * count[2]);  // about 3:1
  EXPECT_GT(count[2], 20u);
}

TEST(MixedCrowd, GroupsScaleToTheCrowdSize) {
  CrowdOptions options;
  options.groups = {
      {0, 80, ActionChoice::Shared, 0, {}}, {1, 40, ActionChoice::Shared, 0, {}}, {2, 40, ActionChoice::Shared, 0, {}}};
  options.copies = 160;
  EXPECT_EQ(crowd_groups(options)[0].copies, 80u);
  options.copies = 16;
  std::vector<CrowdGroup> scaled = crowd_groups(options);
  EXPECT_EQ(scaled[0].copies + scaled[1].copies + scaled[2].copies, 16u);
  EXPECT_EQ(scaled[0].copies, 8u);
  options.copies = 7;
  scaled = crowd_groups(options);
  EXPECT_EQ(scaled[0].copies + scaled[1].copies + scaled[2].copies, 7u);
}

TEST(MixedCrowd, JitterMovesCopiesBySeedOnly) {
  CrowdOptions options;
  options.copies = 20;
  Crowd grid = make_crowd(*characters()[0], options);
  options.layout.jitter = 0.5f;
  options.layout.jitter_seed = 3;
  Crowd a = make_crowd(*characters()[0], options), b = make_crowd(*characters()[0], options);
  for (size_t i = 0; i < 20; ++i) {
    glm::vec3 d = glm::vec3(a.world[i][3]) - glm::vec3(grid.world[i][3]);
    EXPECT_LE(std::abs(d.x), 0.5f);
    EXPECT_LE(std::abs(d.z), 0.5f);
    EXPECT_EQ(a.world[i], b.world[i]);
  }
  EXPECT_NE(a.world[0], grid.world[0]);
  options.layout.rows = 2;
  EXPECT_EQ(make_crowd(*characters()[0], options).rows, 2u);
}

// Blender's default camera: a 35 mm lens on a 32 mm sensor fitted to the
// larger side is 49.13 degrees across a 16:9 frame, 28.84 degrees up it.
TEST(Camera, BlenderConventionFieldOfView) {
  auto degrees = [](float radians) { return radians * 180.0f / 3.14159265f; };
  Lens lens;
  EXPECT_NEAR(degrees(lens.fov_x(16.0f / 9.0f)), 49.134f, 0.01f);
  EXPECT_NEAR(degrees(lens.fov_y(16.0f / 9.0f)), 28.841f, 0.01f);
  // Portrait: the larger side is the height, which the sensor now spans.
  EXPECT_NEAR(degrees(lens.fov_y(9.0f / 16.0f)), 49.134f, 0.01f);
  lens.fit = SensorFit::Horizontal;
  EXPECT_NEAR(degrees(lens.fov_x(9.0f / 16.0f)), 49.134f, 0.01f);
  lens.fit = SensorFit::Vertical;  // Blender's sensor height, 18 mm, spans the height
  EXPECT_NEAR(degrees(lens.fov_y(16.0f / 9.0f)), 28.841f, 0.01f);
  lens.fit = SensorFit::Auto;
  lens.focal_mm = 50.0f;
  EXPECT_NEAR(degrees(lens.fov_x(16.0f / 9.0f)), 35.489f, 0.01f);
  // The projection uses that vertical angle.
  Camera camera;
  glm::mat4 p = camera.projection();
  EXPECT_NEAR(p[1][1], 1.0f / std::tan(0.5f * camera.lens.fov_y(camera.aspect)), 1e-5f);
  EXPECT_NEAR(p[0][0], 1.0f / std::tan(0.5f * camera.lens.fov_x(camera.aspect)), 1e-5f);
}

TEST(Camera, ClosePresetShowsAFewCopiesAndAllShowsEvery) {
  BenchConfig config;
  config.mode = find_mode("culled")->switches;
  config.crowd.copies = 160;
  config.camera = "close";
  CrowdBench close(*characters()[0], config);
  uint64_t visible = close.step().counters.copies_visible;
  EXPECT_GE(visible, 2u);
  EXPECT_LE(visible, 12u);
  config.camera = "all";
  CrowdBench all(*characters()[0], config);
  EXPECT_EQ(all.step().counters.copies_visible, 160u);
  config.lens.focal_mm = 200.0f;  // a long lens: "all" steps back to keep every copy
  CrowdBench tele(*characters()[0], config);
  EXPECT_EQ(tele.step().counters.copies_visible, 160u);
}

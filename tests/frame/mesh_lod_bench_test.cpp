// Mesh LOD in the frame loop (issue 29): each copy's level from its size on
// screen, its skinning at that level on the CPU (the same bits on any thread
// count and in master as in threaded), and the counters per level adding up.
#include <gtest/gtest.h>

#include "asset/standing.h"
#include "frame/crowd_bench.h"
#include "frame/run_bench.h"
#include "render_support.h"

using namespace crowdprof;

namespace {

BenchConfig lod_config(const std::string& mode, int threads, size_t copies = 1000) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode.mesh_lod = true;
  config.mode_name = mode;
  config.threads = threads;
  config.crowd.copies = copies;
  return config;
}

}  // namespace

TEST(MeshLodBench, FarCopiesSkinFewerVerticesAndTheCountersAddUp) {
  const Character& humanoid = test::default_humanoid();
  CrowdBench lod(humanoid, lod_config("threaded", 2));
  BenchConfig plain_config = lod_config("threaded", 2);
  plain_config.mode.mesh_lod = false;
  CrowdBench plain(humanoid, plain_config);
  Counters with = lod.step().counters, without = plain.step().counters;
  ASSERT_EQ(with.copies_visible, without.copies_visible);
  // At 1,000 copies from the default camera no copy spans a quarter of the screen.
  EXPECT_EQ(with.lod0_copies, 0u);
  EXPECT_EQ(with.lod0_copies + with.lod1_copies + with.lod2_copies + with.lod3_copies, with.copies_visible);
  EXPECT_GT(with.lod2_copies + with.lod3_copies, with.copies_visible / 2);
  EXPECT_EQ(with.lod0_vertices + with.lod1_vertices + with.lod2_vertices + with.lod3_vertices, with.vertices_skinned);
  EXPECT_LT(with.vertices_skinned, without.vertices_skinned / 3);
  // Without mesh LOD every copy is level 0.
  EXPECT_EQ(without.lod0_copies, without.copies_visible);
  EXPECT_EQ(without.lod0_vertices, without.vertices_skinned);
  EXPECT_EQ(without.lod0_triangles, without.copies_visible * humanoid.mesh.triangle_count());
  EXPECT_LT(with.lod0_triangles + with.lod1_triangles + with.lod2_triangles + with.lod3_triangles,
            without.lod0_triangles / 3);
  // Each copy's skinned vertices are its level's.
  for (size_t i = 0; i < lod.crowd().size(); ++i) {
    if (!lod.visible(i)) continue;
    EXPECT_LE(lod.skinned_positions(i).size(), humanoid.mesh.vertex_count());
    if (lod.mesh_level(i) > 0) {
      EXPECT_LT(lod.skinned_positions(i).size(), humanoid.mesh.vertex_count());
    }
  }
}

TEST(MeshLodBench, TheSameBitsOnAnyThreadsAndInMaster) {
  const Character& humanoid = test::default_humanoid();
  CrowdBench one(humanoid, lod_config("threaded", 1, 200));
  CrowdBench two(humanoid, lod_config("threaded", 2, 200));
  CrowdBench master(humanoid, lod_config("master", 1, 200));
  for (int f = 0; f < 3; ++f) {
    one.step();
    two.step();
    master.step();
  }
  EXPECT_EQ(one.digest(), two.digest());
  EXPECT_EQ(one.digest(), master.digest());
  BenchConfig plain = lod_config("threaded", 1, 200);
  plain.mode.mesh_lod = false;
  CrowdBench full(humanoid, plain);
  for (int f = 0; f < 3; ++f) full.step();
  EXPECT_NE(one.digest(), full.digest()) << "the levels are not what was skinned";
}

TEST(MeshLodBench, ThresholdsOfZeroKeepEveryCopyWhole) {
  BenchConfig config = lod_config("threaded", 1, 200);
  config.mode.mesh_lod_at = {0, 0, 0};
  CrowdBench bench(test::default_humanoid(), config);
  Counters c = bench.step().counters;
  EXPECT_EQ(c.lod0_copies, c.copies_visible);
  EXPECT_EQ(c.lod1_copies + c.lod2_copies + c.lod3_copies, 0u);
  // Every copy drawn whole is the run without mesh LOD: the same digest.
  BenchConfig plain = config;
  plain.mode.mesh_lod = false;
  CrowdBench full(test::default_humanoid(), plain);
  full.step();
  EXPECT_EQ(bench.digest(), full.digest());
}

TEST(MeshLodBench, SharingIsRefusedNamingTheSwitchEveryModeTakesIt) {
  ModeSwitches shared = find_mode("shared")->switches;
  shared.mesh_lod = true;
  EXPECT_NE(conflicts(shared).str().find("mesh_lod"), std::string::npos) << conflicts(shared).str();
  ModeSwitches culled_on_gpu = find_mode("baked")->switches;
  culled_on_gpu.frustum = FrustumTest::Gpu;
  culled_on_gpu.mesh_lod = true;
  EXPECT_TRUE(conflicts(culled_on_gpu).empty()) << conflicts(culled_on_gpu).str();
  for (const char* mode : {"master", "culled", "threaded", "hwskin", "buffer", "instanced", "compute", "baked"}) {
    ModeSwitches s = find_mode(mode)->switches;
    s.mesh_lod = true;
    EXPECT_TRUE(conflicts(s).empty()) << mode << ": " << conflicts(s).str();
  }
}

TEST(MeshLodBench, CopiesOffScreenAreSkinnedAtTheCoarsestLevelWithCullingOff) {
  BenchConfig config = lod_config("master", 1, 200);
  CrowdBench bench(test::default_humanoid(), config);
  bench.step();
  size_t off_screen = 0;
  for (size_t i = 0; i < bench.crowd().size(); ++i) {
    if (bench.visible(i)) continue;
    ++off_screen;
    EXPECT_EQ(bench.mesh_level(i), 3u) << i;
  }
  EXPECT_GT(off_screen, 0u);
}

// The run's record: copies per level as the counters say, each level's error
// (meshoptimizer's, growing level by level) in model units, as a share of the
// height and in pixels where copies are drawn at it.
TEST(MeshLodBench, TheRunRecordsEachLevelsCopiesAndError) {
  CrowdBench bench(test::default_humanoid(), lod_config("threaded", 1, 1000));
  Counters c = bench.step().counters;
  Result report;
  record_mesh_lod(bench, report);
  ASSERT_TRUE(report.mesh_lod);
  const MeshLodRecord& m = *report.mesh_lod;
  ASSERT_EQ(m.levels.size(), 4u);
  EXPECT_EQ(m.levels[0].copies, c.lod0_copies);
  EXPECT_EQ(m.levels[2].copies, c.lod2_copies);
  EXPECT_EQ(m.levels[3].copies, c.lod3_copies);
  EXPECT_EQ(m.levels[0].error, 0.0);
  for (size_t l = 1; l < 4; ++l) {
    EXPECT_GT(m.levels[l].error, m.levels[l - 1].error) << l;
    EXPECT_NEAR(m.levels[l].error_fraction, m.levels[l].error / standing_of(test::default_humanoid()).height, 1e-9)
        << l;
    EXPECT_EQ(m.levels[l].error_px > 0, m.levels[l].copies > 0) << l;
  }
  // 1,000 humanoids from the default camera are a few dozen pixels tall: under a pixel of error.
  EXPECT_LT(m.levels[3].error_px, 1.0);
  BenchConfig plain = lod_config("threaded", 1, 10);
  plain.mode.mesh_lod = false;
  CrowdBench without(test::default_humanoid(), plain);
  Result none;
  record_mesh_lod(without, none);
  EXPECT_FALSE(none.mesh_lod);
}

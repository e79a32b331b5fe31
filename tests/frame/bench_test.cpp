// The frame loop: modes and thread counts agree bit for bit on drawn copies,
// culling does what the camera says, and the reports add up and parse.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include "base/errors.h"
#include "gen/humanoid.h"
#include "frame/run_bench.h"
#include "reports/profile_table.h"
#include "result/result_codec.h"
#include "test_support.h"
#include "characters.h"

using namespace crowdprof;

namespace {

using test::small_humanoid;

BenchConfig config_for(const std::string& mode, int threads = 1, size_t copies = 24) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode_name = mode;
  config.threads = threads;
  config.crowd.copies = copies;
  config.crowd.actions = ActionChoice::Random;
  config.crowd.seed = 3;
  return config;
}

void run_frames(CrowdBench& bench, int frames) {
  for (int i = 0; i < frames; ++i) bench.step();
}

}  // namespace

TEST(Bench, AnyThreadCountGivesTheSameBits) {
  CrowdBench one(small_humanoid(), config_for("threaded", 1));
  run_frames(one, 4);
  for (int threads : {2, 3, 8}) {
    CrowdBench many(small_humanoid(), config_for("threaded", threads));
    run_frames(many, 4);
    EXPECT_EQ(one.digest(), many.digest()) << threads << " threads";
    for (size_t c = 0; c < one.crowd().size(); ++c) {
      auto a = one.skinned_positions(c), b = many.skinned_positions(c);
      ASSERT_EQ(0, std::memcmp(a.data(), b.data(), a.size_bytes())) << "copy " << c;
    }
  }
}

TEST(Bench, ModesAgreeOnTheCopiesTheyDraw) {
  CrowdBench master(small_humanoid(), config_for("master"));
  CrowdBench culled(small_humanoid(), config_for("culled"));
  CrowdBench threaded(small_humanoid(), config_for("threaded", 2));
  run_frames(master, 5);
  run_frames(culled, 5);
  run_frames(threaded, 5);
  EXPECT_EQ(master.digest(), culled.digest());
  EXPECT_EQ(master.digest(), threaded.digest());
  for (size_t c = 0; c < master.crowd().size(); ++c) {
    if (!master.visible(c)) continue;
    auto a = master.skinned_normals(c), b = threaded.skinned_normals(c);
    ASSERT_EQ(0, std::memcmp(a.data(), b.data(), a.size_bytes())) << "copy " << c;
  }
}

TEST(Bench, CountersFollowTheSwitches) {
  const size_t copies = 40;
  CrowdBench master(small_humanoid(), config_for("master", 1, copies));
  CrowdBench culled(small_humanoid(), config_for("culled", 1, copies));
  CrowdBench threaded(small_humanoid(), config_for("threaded", 2, copies));
  FrameRecord m = master.step(), c = culled.step(), t = threaded.step();
  size_t channels = 0;
  for (size_t i = 0; i < copies; ++i) channels += small_humanoid().actions[master.crowd().action[i]].channels.size();
  // master: every copy posed and skinned, every channel looked up by string.
  EXPECT_EQ(m.counters.poses_updated, copies);
  EXPECT_EQ(m.counters.copies_culled, 0u);
  EXPECT_EQ(m.counters.vertices_skinned, copies * 800);
  EXPECT_EQ(m.counters.channel_lookups, channels);
  // The default camera leaves part of the crowd off-screen, as the thesis scene did.
  EXPECT_GT(c.counters.copies_culled, 0u);
  EXPECT_LT(c.counters.copies_visible, copies);
  EXPECT_EQ(c.counters.copies_culled + c.counters.poses_updated, copies);
  EXPECT_EQ(c.counters.copies_visible, c.counters.poses_updated);
  EXPECT_EQ(t.counters.channel_lookups, 0u);
  EXPECT_EQ(t.counters.poses_updated, c.counters.poses_updated);
  // Where skinning is charged: Rasterizer in master, Animations in threaded.
  EXPECT_GT(m.times[Category::Rasterizer], 0.0);
  EXPECT_EQ(t.counters.vertices_skinned, c.counters.vertices_skinned);
}

TEST(Bench, CategoriesAddUpToTheWallClock) {
  CrowdBench bench(small_humanoid(), config_for("master", 1, 60));
  bench.step();
  auto start = std::chrono::steady_clock::now();
  double sum = 0;
  for (int i = 0; i < 5; ++i) sum += bench.step().times.total_ms();
  double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NEAR(sum, wall, wall * 0.01);
}

TEST(Culling, BoxesAgainstAKnownCamera) {
  Camera camera;
  camera.eye = glm::vec3(0, 0, 0);
  camera.target = glm::vec3(0, 0, -1);
  // 90 degrees vertically: a sensor as tall as twice the focal length.
  camera.lens.fit = SensorFit::Vertical;
  camera.lens.focal_mm = 9.0f;
  camera.lens.sensor_height_mm = 18.0f;
  camera.aspect = 1.0f;
  camera.near_plane = 0.1f;
  camera.far_plane = 100.0f;
  Frustum f = frustum_of(camera.view_projection());
  auto box = [](glm::vec3 c) { return Aabb{c - glm::vec3(0.5f), c + glm::vec3(0.5f)}; };
  EXPECT_TRUE(intersects(f, box({0, 0, -10})));       // straight ahead
  EXPECT_FALSE(intersects(f, box({0, 0, 10})));       // behind
  EXPECT_FALSE(intersects(f, box({-20, 0, -10})));    // left of a 90 degree view at 10 m (edge at x = -10)
  EXPECT_TRUE(intersects(f, box({-10.4f, 0, -10})));  // straddles the left edge
  EXPECT_FALSE(intersects(f, box({0, 0, -101})));     // past the far plane
  EXPECT_FALSE(intersects(f, box({0, 12, -10})));     // above
}

TEST(Culling, CrowdCopiesOutsideACustomCameraAreSkipped) {
  BenchConfig config = config_for("culled", 1, 16);
  // Looking along -X from far right of the crowd: only some columns can be seen.
  CrowdBench probe(small_humanoid(), config);
  const Aabb& crowd = probe.crowd().crowd_box;
  glm::vec3 eye(crowd.max.x + 1.0f, 1.0f, crowd.center().z);
  // Looking away from the crowd: nothing visible, nothing posed.
  config.camera = std::to_string(eye.x) + ",1," + std::to_string(eye.z) + "," + std::to_string(eye.x + 10) + ",1," +
                  std::to_string(eye.z);
  CrowdBench away(small_humanoid(), config);
  FrameRecord r = away.step();
  EXPECT_EQ(r.counters.copies_visible, 0u);
  EXPECT_EQ(r.counters.poses_updated, 0u);
  config.camera = "all";
  CrowdBench all(small_humanoid(), config);
  EXPECT_EQ(all.step().counters.copies_culled, 0u);
}

TEST(Culling, ACameraLookingStraightDownSeesTheCrowd) {
  BenchConfig config = config_for("culled", 1, 16);
  CrowdBench probe(small_humanoid(), config);
  const Aabb& crowd = probe.crowd().crowd_box;
  glm::vec3 c = crowd.center();
  for (float height : {30.0f, -30.0f}) {  // from above, and from below looking up
    std::string spec = std::to_string(c.x) + "," + std::to_string(c.y + height) + "," + std::to_string(c.z) + "," +
                       std::to_string(c.x) + "," + std::to_string(c.y) + "," + std::to_string(c.z);
    Camera camera = make_camera(spec, crowd, 16.0f / 9.0f);
    glm::mat4 m = camera.view_projection();
    for (int i = 0; i < 16; ++i) ASSERT_TRUE(std::isfinite(m[i / 4][i % 4])) << spec;
    config.camera = spec;
    CrowdBench above(small_humanoid(), config);
    EXPECT_GT(above.step().counters.copies_visible, 0u) << spec;
  }
}

TEST(Reports, CsvAndJsonParseAndAddUp) {
  CrowdBench bench(small_humanoid(), config_for("master", 1, 12));
  RunOptions options;
  options.frames = 4;
  options.warmup = 1;
  Result report = run_bench(bench, "humanoid", options);
  ASSERT_EQ(report.frame_records.size(), 4u);

  std::stringstream csv;
  write_csv(report, csv);
  std::string line;
  std::getline(csv, line);
  size_t columns = std::count(line.begin(), line.end(), ',') + 1;
  // then gpu_ms, cpu_ms, Animations by stage and the counters added since
  const size_t later = kCounterFields.size() - kCsvCountersBeforeGpu;
  EXPECT_EQ(columns, 5 + kCategoryCount + kCounterFields.size() + 2 + kAnimationStageCount);
  EXPECT_TRUE(
      line.ends_with(",gpu_ms,cpu_ms,animation_sampling_ms,animation_blending_ms,animation_local_to_model_ms,"
                     "animation_skinning_ms,layers"))
      << line;
  EXPECT_EQ(line.rfind("frame,mode,characters,threads,frame_ms,physics_ms", 0), 0u);
  int rows = 0;
  std::vector<double> cpu;
  while (std::getline(csv, line)) {
    ++rows;
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), columns);
    double frame = std::stod(cells[4]), sum = 0;
    for (size_t c = 0; c < kCategoryCount; ++c) sum += std::stod(cells[5 + c]);
    EXPECT_NEAR(sum, frame, frame * 0.01);
    cpu.push_back(std::stod(cells[cells.size() - 1 - kAnimationStageCount - later]));
  }
  EXPECT_EQ(rows, 4);

  nlohmann::json j = nlohmann::json::parse(result_to_json(report).dump());
  EXPECT_EQ(j["mode"], "master");
  EXPECT_EQ(j["frames"], 4);
  ASSERT_EQ(j["samples"]["cpu_ms"].size(), cpu.size());
  for (size_t i = 0; i < cpu.size(); ++i)  // the CSV's cpu_ms is the JSON's, to its 4 decimals
    EXPECT_NEAR(cpu[i], j["samples"]["cpu_ms"][i].get<double>(), 1e-4);
  EXPECT_EQ(j["scene"]["characters"], 12);
  EXPECT_EQ(j["scene"]["joints"], 30);
  EXPECT_EQ(j["categories"].size(), kCategoryCount);
  for (const char* name : {"physics_ms", "logic_ms", "animations_ms", "network_ms", "scenegraph_ms", "rasterizer_ms",
                           "services_ms", "overhead_ms", "outside_ms", "gpu_latency_ms"})
    for (const char* field : {"min_ms", "median_ms", "mean_ms", "p95_ms", "max_ms", "stddev_ms"})
      EXPECT_TRUE(j["categories"][name].contains(field)) << name << " " << field;
  EXPECT_EQ(j["counters"]["poses_updated"], 12);
  EXPECT_EQ(j["digest"], bench.digest());
  EXPECT_EQ(j["samples"]["frame_ms"].size(), 4u);
  double categories = 0;
  for (auto& [name, summary] : j["categories"].items()) categories += summary["mean_ms"].get<double>();
  EXPECT_NEAR(categories, j["frame"]["mean_ms"].get<double>(), j["frame"]["mean_ms"].get<double>() * 0.01);
}

TEST(Bench, RefusesACrowdThatCannotFit) {
  EXPECT_THROW(check_fits_in_memory(small_humanoid(), 9'000'000'000ull, find_mode("threaded")->switches), UsageError);
  EXPECT_NO_THROW(check_fits_in_memory(small_humanoid(), 10, find_mode("threaded")->switches));
}

TEST(Bench, SharedPoseCannotRunInParallel) {
  BenchConfig config = config_for("master");
  config.mode.parallel = true;
  EXPECT_THROW(CrowdBench(small_humanoid(), config), UsageError);
}

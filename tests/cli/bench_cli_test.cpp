// `crowdprof bench` from the outside: bad command lines exit 2 with one line on
// stderr, bad files exit 3, and a good run prints the profile.
#include <gtest/gtest.h>

#include <filesystem>

#include "gen/gltf_writer.h"
#include "gen/humanoid.h"
#include "test_support.h"

using crowdprof::test::humanoid_glb;
using crowdprof::test::run_cli;

namespace {

void expect_bench_usage_error(const std::string& args, const std::string& words) {
  auto r = run_cli("bench '" + humanoid_glb() + "' " + args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

}  // namespace

TEST(BenchCli, RunsTheDefaultSceneAndPrintsTheProfile) {
  auto r = run_cli("bench '" + humanoid_glb() + "' -n 6 --frames 3 --warmup 1 --mode culled");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* line : {"Frametime :", "Physics", "Animations :", "Rasterizer :", "GPU Latency:", "mode culled",
                           "copies culled", "digest"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;  // no progress when stderr is not a terminal
}

TEST(BenchCli, BadNumbersAndNames) {
  expect_bench_usage_error("-n 0", "at least 1");
  expect_bench_usage_error("-n -4", "at least 1");
  expect_bench_usage_error("-n many", "--characters");
  expect_bench_usage_error("--frames 0", "--frames");
  expect_bench_usage_error("--warmup -1", "--warmup");
  expect_bench_usage_error("--fps 0", "--fps");
  expect_bench_usage_error("--mode fastest", "master, culled, threaded, hwskin");
  expect_bench_usage_error("--threads 0", "--threads");
  expect_bench_usage_error("--mode master --threads 4", "one thread");
  expect_bench_usage_error("--actions sometimes", "shared, random");
  expect_bench_usage_error("--action tango", "dance");
  expect_bench_usage_error("--camera 1,2,3", "--camera");
  expect_bench_usage_error("--culling maybe", "on or off");
  expect_bench_usage_error("--mode master --parallel on", "shared scratch pose");
  expect_bench_usage_error("--backend vulkan", "--backend");
  expect_bench_usage_error("-n 9000000", "memory");
}

TEST(BenchCli, BadFilesExit3) {
  auto r = run_cli("bench /nonexistent/crowd.glb");
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("crowdprof: /nonexistent/crowd.glb: no such file"), std::string::npos) << r.err;
}

TEST(BenchCli, ACharacterWithoutSkinOrActions) {
  CROWDPROF_REQUIRE_SAMPLES();
  auto r = run_cli("bench '" + crowdprof::test::sample("InterpolationTest/glTF-Binary/InterpolationTest.glb") + "'");
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("has no skin"), std::string::npos) << r.err;
}

// A character without actions is refused (its crowd would stand still, which is
// rarely what was meant) unless --static asks for exactly that.
TEST(BenchCli, ACharacterWithoutActionsNeedsStatic) {
  crowdprof::Character character = crowdprof::generate_humanoid({30, 800, 7});
  character.actions.clear();
  auto dir = crowdprof::test::scratch_dir("bench_static");
  std::string file = (dir / "still.glb").string();
  crowdprof::write_gltf(character, file);

  auto refused = run_cli("bench '" + file + "' -n 4 --frames 2 --warmup 0");
  EXPECT_EQ(refused.status, 2) << refused.err;
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  EXPECT_NE(refused.err.find("has no actions"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--static"), std::string::npos) << refused.err;

  auto still = run_cli("bench '" + file + "' -n 4 --frames 2 --warmup 0 --static --mode master");
  EXPECT_EQ(still.status, 0) << still.err;
  EXPECT_NE(still.out.find("4 characters x 30 joints"), std::string::npos) << still.out;
  EXPECT_NE(still.out.find("0 lookups per frame"), std::string::npos) << still.out;

  // A baseline of a static crowd reruns as one: check adopts --static.
  std::string base = (dir / "still.json").string();
  ASSERT_EQ(run_cli("bench '" + file + "' -n 4 --frames 8 --warmup 0 --static -q --json '" + base + "'").status, 0);
  auto check = run_cli("check --spread 0 --baseline '" + base + "' --tolerance 900%");
  EXPECT_EQ(check.status, 0) << check.out << check.err;
}

// A path that cannot take an output is a command-line error, found before the
// run when it can be (a missing folder, a directory) and after it when only
// writing tells (a full disk); stdout stays empty either way.
TEST(BenchCli, OutputsThatCannotBeWritten) {
  auto dir = crowdprof::test::scratch_dir("bench_outputs");
  std::string missing = (dir / "no" / "frames.csv").string();
  expect_bench_usage_error("-n 2 --frames 1 --csv '" + missing + "'",
                           "cannot write CSV file '" + missing + "': no folder " + (dir / "no").string());
  expect_bench_usage_error("-n 2 --frames 1 --json '" + dir.string() + "'",
                           "cannot write JSON file '" + dir.string() + "': it is a directory");
  if (std::filesystem::is_character_file("/dev/full"))
    expect_bench_usage_error("-n 2 --frames 1 -q --trace /dev/full",
                             "cannot write trace file '/dev/full': No space left on device");
}

// Baselines remember where they came from: the scene file is stored relative
// to the baseline and found from any folder; a missing one is said to come from
// the baseline; another machine or build is one warning line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "gate/regression.h"
#include "result/result_codec.h"
#include "test_support.h"

using crowdprof::test::run_cli;
using nlohmann::json;
namespace fs = std::filesystem;

TEST(BaselineOrigin, TheSceneIsFoundFromTheBaselinesFolderFromAnywhere) {
  auto dir = crowdprof::test::scratch_dir("baseline_origin");
  fs::create_directories(dir / "ci" / "perf");
  fs::create_directories(dir / "assets");
  fs::copy_file(crowdprof::test::source_dir() / "scenes" / "humanoid.glb", dir / "assets" / "hero.glb");
  std::string base = (dir / "ci" / "perf" / "base.json").string();
  // Recorded from the top folder with a relative scene path.
  std::string cd = "cd '" + dir.string() + "' && '" + CROWDPROF_CLI + "' ";
  ASSERT_EQ(std::system((cd + "check --spread 0 assets/hero.glb -n 4 --frames 10 --warmup 1 --mode culled --attempts 1 "
                              "--baseline ci/perf/base.json --update-baseline -q")
                            .c_str()),
            0);
  json recorded = json::parse(std::ifstream(base));
  EXPECT_EQ(recorded["scene"]["file"], "../../assets/hero.glb");
  EXPECT_EQ(recorded["scene"]["file_from"], "result");
  // Checked from another folder (the test's own), naming only the baseline.
  auto r = run_cli("check --spread 0 --baseline '" + base + "' --tolerance 900% --floor 10s");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  // The scene gone: the error says the path came from the baseline.
  fs::remove(dir / "assets" / "hero.glb");
  r = run_cli("check --spread 0 --baseline '" + base + "'");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(r.err.rfind("crowdprof: " + base + ": its scene file: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("the path the baseline recorded, resolved from the baseline's folder"), std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(BaselineOrigin, PathsRelativeToTheResultKeepTheSkin) {
  json doc = {{"scene", {{"file", "/data/chars/fox.glb#skin=1"}}}};
  json moved = crowdprof::with_paths_relative_to(doc, "/data/results/r.json");
  EXPECT_EQ(moved["scene"]["file"], "../chars/fox.glb#skin=1");
  EXPECT_EQ(moved["scene"]["file_from"], "result");
  crowdprof::Result stored;
  stored.run.file = moved["scene"]["file"];
  stored.file_from_result = true;
  EXPECT_EQ(crowdprof::recorded_scene_file(stored, "/data/results/r.json"), "/data/chars/fox.glb#skin=1");
  // An older result (no file_from) keeps its path as recorded.
  crowdprof::Result older;
  older.run.file = doc["scene"]["file"];
  EXPECT_EQ(crowdprof::recorded_scene_file(older, "/elsewhere/r.json"), "/data/chars/fox.glb#skin=1");
}

TEST(BaselineOrigin, AnotherMachineOrBuildIsOneWarningLine) {
  auto dir = crowdprof::test::scratch_dir("baseline_machine");
  std::string scene = (crowdprof::test::source_dir() / "scenes" / "humanoid.glb").string();
  std::string base = (dir / "base.json").string();
  ASSERT_EQ(
      run_cli("bench '" + scene + "' -n 4 --frames 10 --warmup 1 --mode culled --calibrate -q --json '" + base + "'")
          .status,
      0);
  json other = json::parse(std::ifstream(base));
  other["environment"]["cpu"] = "Another CPU";
  other["environment"]["build_type"] = "Another build type";
  std::ofstream(dir / "other.json") << other.dump();
  auto r = run_cli("check --result '" + base + "' --baseline '" + (dir / "other.json").string() + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(
      r.err.rfind("crowdprof: warning: the baseline was measured on another machine or build (cpu \"Another CPU\" "
                  "there, ",
                  0),
      0u)
      << r.err;
  EXPECT_NE(r.err.find("build_type \"Another build type\" there, "), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  // The same machine and build: nothing.
  r = run_cli("check --result '" + base + "' --baseline '" + base + "'");
  EXPECT_TRUE(r.err.empty()) << r.err;
}

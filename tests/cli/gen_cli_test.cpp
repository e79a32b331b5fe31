// `crowdprof gen`: writes the humanoid, says what it wrote, refuses bad options.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "asset/gltf_loader.h"
#include "test_support.h"

using namespace crowdprof;

TEST(GenCli, WritesWhatItSays) {
  auto dir = test::scratch_dir("gen_cli");
  const std::string file = (dir / "small.glb").string();
  test::CliResult r = test::run_cli("gen -o '" + file + "' --bones 30 --vertices 800 --seed 9");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "wrote " + file + ": 30 joints, 800 vertices, 3 actions, " +
                       std::to_string(std::filesystem::file_size(file)) + " bytes\n");
  Character c = load_character(file);
  EXPECT_EQ(c.skeleton.joint_count(), 30u);
  EXPECT_EQ(c.mesh.vertex_count(), 800u);
}

TEST(GenCli, LocomotionWritesIdleWalkAndRun) {
  auto dir = test::scratch_dir("gen_cli_locomotion");
  const std::string file = (dir / "locomotion.glb").string();
  test::CliResult r = test::run_cli("gen -o '" + file + "' --actions locomotion");
  ASSERT_EQ(r.status, 0) << r.err;
  Character c = load_character(file);
  ASSERT_EQ(c.actions.size(), 3u);
  EXPECT_EQ(c.actions[0].name, "idle");
  EXPECT_EQ(c.actions[1].name, "walk");
  EXPECT_EQ(c.actions[2].name, "run");
  EXPECT_EQ(c.skeleton.joint_count(), 69u);
  EXPECT_EQ(test::run_cli("gen -o '" + file + "' --actions dance").status, 2) << "unknown set";
}

TEST(GenCli, FormatFollowsTheExtension) {
  auto dir = test::scratch_dir("gen_cli_format");
  auto first_byte = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return char(in.get());
  };
  ASSERT_EQ(test::run_cli("gen -o '" + (dir / "a.gltf").string() + "'").status, 0);
  EXPECT_EQ(first_byte(dir / "a.gltf"), '{');
  ASSERT_EQ(test::run_cli("gen -o '" + (dir / "a.glb").string() + "' --draco").status, 0);
  EXPECT_EQ(first_byte(dir / "a.glb"), 'g');
  EXPECT_TRUE(load_character((dir / "a.glb").string()).draco_decoded);
  ASSERT_EQ(test::run_cli("gen -o '" + (dir / "a.json").string() + "' --gltf").status, 0);
  EXPECT_EQ(first_byte(dir / "a.json"), '{');
}

TEST(GenCli, BadOptionsExit2AndBadPathsExit3) {
  auto dir = test::scratch_dir("gen_cli_bad");
  const std::string file = (dir / "x.glb").string();
  for (std::string args :
       {"--bones 19", "--bones 5000", "--vertices 10", "--vertices 2500001", "--bones many", "--gltf"}) {
    test::CliResult r = test::run_cli("gen -o '" + file + "' " + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_NE(r.err, "") << args;
    EXPECT_FALSE(std::filesystem::exists(file)) << args;
  }
  EXPECT_EQ(test::run_cli("gen").status, 2) << "-o is required";
  const std::string nowhere = (dir / "no" / "such" / "dir.glb").string();
  test::CliResult r = test::run_cli("gen -o '" + nowhere + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "crowdprof: cannot write GLB file '" + nowhere + "': no folder " + (dir / "no" / "such").string() + "\n");
}

// Modes compute and baked from the outside (issue 12): the report's line and
// JSON say what baking cost and how far it strays, bad rates and a missing
// backend are refused with exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "test_support.h"

using crowdprof::test::humanoid_glb;
using crowdprof::test::read_json;
using crowdprof::test::run_cli;

TEST(GpuSkinningCli, BakedReportsItsBakeAndDeviation) {
  if (!crowdprof::test::have_gl()) GTEST_SKIP() << "no GL backend on this machine";
  auto result_file = crowdprof::test::scratch_dir("gpu_skinning_cli") / "baked.json";
  auto r = run_cli("bench '" + humanoid_glb() +
                   "' -n 12 --mode baked --backend auto --resolution 160x90 --frames 2 --warmup 0 "
                   "--bake-rate 15 --json '" +
                   result_file.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("skinning baked |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("baked at 15 Hz"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("largest vertex deviation from exact sampling"), std::string::npos) << r.out;
  nlohmann::json j = read_json(result_file);
  const nlohmann::json& g = j.at("gpu_skinning");
  EXPECT_EQ(g.at("skinning"), "baked");
  EXPECT_EQ(g.at("rate_hz"), 15.0);
  EXPECT_GT(g.at("max_deviation").get<double>(), 0.0);
  EXPECT_GT(g.at("max_deviation_fraction").get<double>(), 0.0);
  EXPECT_LT(g.at("max_deviation_fraction").get<double>(), 0.05);  // a few percent would be visibly wrong
  EXPECT_GT(g.at("gpu_bytes").get<uint64_t>(), 0u);
  EXPECT_EQ(j.at("switches").at("skinning"), "baked");
  EXPECT_EQ(j.at("digest_cpu_vertices"), false) << "the renderer skinned every copy";
  const nlohmann::json& k = j.at("counters");
  EXPECT_EQ(k.at("draw_calls"), 1);
  // A 16-byte record a copy on screen (render/gpu_frame_buffers.h, GpuInstance):
  // the median frame sends no placement (they went up once).
  EXPECT_EQ(k.at("bytes_uploaded").get<uint64_t>(), 16 * k.at("copies_visible").get<uint64_t>());
  EXPECT_EQ(k.at("record_bytes_uploaded").get<uint64_t>(), 16 * k.at("copies_visible").get<uint64_t>());
  EXPECT_EQ(k.at("palette_bytes_uploaded").get<uint64_t>(), 0u);
  EXPECT_EQ(k.at("poses_updated"), 0);
}

TEST(GpuSkinningCli, ComputeReportsItsGpuMemory) {
  if (!crowdprof::test::have_gl()) GTEST_SKIP() << "no GL backend on this machine";
  auto result_file = crowdprof::test::scratch_dir("gpu_skinning_cli") / "compute.json";
  auto r = run_cli("bench '" + humanoid_glb() +
                   "' -n 6 --mode compute --backend auto --resolution 160x90 --frames 2 --warmup 0 "
                   "--json '" +
                   result_file.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json j = read_json(result_file);
  EXPECT_EQ(j.at("gpu_skinning").at("skinning"), "compute");
  EXPECT_FALSE(j.at("gpu_skinning").contains("max_deviation"));
  EXPECT_EQ(j.at("counters").at("draw_calls"), j.at("counters").at("copies_visible"));
}

TEST(GpuSkinningCli, RefusesWhatCannotRun) {
  for (const char* mode : {"compute", "baked"}) {
    auto r = run_cli("bench '" + humanoid_glb() + "' -n 2 --mode " + std::string(mode) + " --backend none --frames 1");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("needs a GL backend"), std::string::npos) << r.err;
  }
  // The switch on its own, over another preset: parsed, then refused for want of GL.
  auto r = run_cli("bench '" + humanoid_glb() +
                   "' -n 2 --mode hwskin --skinning baked --palettes buffer --draw instanced "
                   "--backend none --frames 1");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("skinning baked) needs a GL backend"), std::string::npos) << r.err;
  r = run_cli("bench '" + humanoid_glb() + "' -n 2 --mode threaded --skinning compute --backend none --frames 1");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--skinning compute reads its matrices from shader storage buffers"), std::string::npos)
      << r.err;
  for (const char* rate : {"0", "-3", "nan", "20000"}) {
    auto bad = run_cli("bench '" + humanoid_glb() + "' -n 2 --mode baked --backend none --frames 1 --bake-rate " +
                       std::string(rate));
    EXPECT_EQ(bad.status, 2) << rate << ": " << bad.err;
    EXPECT_NE(bad.err.find("--bake-rate"), std::string::npos) << bad.err;
  }
}

TEST(GpuSkinningCli, AGlWithoutWhatTheModeNeedsIsOneLineAndExit4) {
  if (!crowdprof::test::have_gl()) GTEST_SKIP() << "no GL backend on this machine";
  for (auto [mode, hide, words] : {std::tuple{"compute", "compute", "needs compute shaders"},
                                   std::tuple{"baked", "vertex-ssbo", "storage buffers in the vertex shader"}}) {
    setenv("CROWDPROF_GL_HIDE", hide, 1);
    auto r = run_cli("bench '" + humanoid_glb() + "' -n 2 --mode " + std::string(mode) +
                     " --backend auto --resolution 160x90 --frames 1 --warmup 0");
    unsetenv("CROWDPROF_GL_HIDE");
    EXPECT_EQ(r.status, 4) << mode << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "") << "nothing reported as measured";
  }
}

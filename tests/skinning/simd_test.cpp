// Run-time SIMD dispatch: every target compiled in and runnable here gives the
// same digest at every thread count, and forcing a target works and says why
// it cannot.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include <nlohmann/json.hpp>

#include "asset/standing.h"
#include "frame/crowd_bench.h"
#include "gen/humanoid.h"
#include "asset/mesh_lod.h"
#include "measuring/environment.h"
#include "skinning/simd_target.h"
#include "skinning/skinning_kernels.h"
#include "test_support.h"
#include "characters.h"

using namespace crowdprof;

namespace {

using test::small_humanoid;

// The humanoid with weights that are not short binary fractions, so that a
// fused multiply-add on one target would round differently from the separate
// multiply and add on another.
const Character& uneven_humanoid() {
  static const Character character = [] {
    Character c = generate_humanoid({30, 800, 7});
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> factor(0.5f, 1.5f);
    for (glm::vec4& w : c.mesh.weights) {
      for (int k = 0; k < 4; ++k) w[k] *= factor(rng);
      w /= w.x + w.y + w.z + w.w;
      std::sort(&w[0], &w[0] + 4, [](float a, float b) { return a > b; });
    }
    return c;
  }();
  return character;
}

// 12 copies, mode threaded, no culling.
BenchConfig twelve_copies(int threads, ActionChoice actions, VertexFormat format = VertexFormat::Float) {
  BenchConfig config;
  config.mode = find_mode("threaded")->switches;
  config.mode.vertex_format = format;
  config.mode.animation_culling = false;
  config.threads = threads;
  config.crowd.copies = 12;
  config.crowd.actions = actions;
  config.crowd.seed = 5;
  return config;
}

std::string digest_of(const Character& character, int threads, ActionChoice actions,
                      VertexFormat format = VertexFormat::Float) {
  CrowdBench bench(character, twelve_copies(threads, actions, format));
  for (int i = 0; i < 3; ++i) bench.step();
  return bench.digest();
}

// Puts the CPU's best target back whatever a test forced.
struct SimdTargetTest : ::testing::Test {
  void TearDown() override { EXPECT_EQ("", force_simd_target("")); }
};

}  // namespace

TEST_F(SimdTargetTest, EveryTargetAndThreadCountGivesTheSameDigest) {
  const std::vector<std::string> targets = available_simd_targets();
  ASSERT_FALSE(targets.empty());
  // x86-64 CPUs of the last 15 years run at least SSSE3 and SSE4 besides the
  // portable baseline (SCALAR, or EMU128 with compilers Highway trusts with it):
  // this test must compare several.
  ASSERT_GE(targets.size(), 3u) << "only " << targets[0];
  EXPECT_TRUE(targets.back() == "SCALAR" || targets.back() == "EMU128") << targets.back();
  const std::string best = active_simd_target();
  EXPECT_EQ(best, targets.front());
  // Every target of one arithmetic (fused multiply-adds on AVX2 and up,
  // separate below) gives the same digest; packed vertices (their bytes are
  // hashed then) too: the codes are rounded from the floats the same way.
  std::set<bool> arithmetics;
  for (VertexFormat format : {VertexFormat::Float, VertexFormat::Packed}) {
    std::map<bool, std::pair<std::string, std::string>> expected;  // by arithmetic: shared, random
    for (const std::string& target : targets) {
      ASSERT_EQ("", force_simd_target(target));
      ASSERT_EQ(target, active_simd_target());
      const bool fused = skinning_fuses_multiply_add();
      arithmetics.insert(fused);
      EXPECT_EQ(fused, target.rfind("AVX", 0) == 0) << target;
      EXPECT_EQ(fused, current_environment().fused_multiply_add) << target;
      for (int threads : {1, 2, 3}) {
        const std::string shared = digest_of(small_humanoid(), threads, ActionChoice::Shared, format);
        const std::string random = digest_of(uneven_humanoid(), threads, ActionChoice::Random, format);
        auto& [expected_shared, expected_random] = expected[fused];
        if (expected_shared.empty()) expected_shared = shared, expected_random = random;
        EXPECT_EQ(expected_shared, shared) << target << ", " << threads << " threads, " << to_string(format);
        EXPECT_EQ(expected_random, random) << target << ", " << threads << " threads, " << to_string(format);
      }
    }
  }
  // Both arithmetics were compared here unless this CPU has no AVX2.
  if (targets.front().rfind("AVX", 0) == 0) {
    EXPECT_EQ(2u, arithmetics.size());
  }
  EXPECT_NE(digest_of(small_humanoid(), 1, ActionChoice::Shared, VertexFormat::Float),
            digest_of(small_humanoid(), 1, ActionChoice::Shared, VertexFormat::Packed));
}

TEST_F(SimdTargetTest, ForcingAnUnknownTargetChangesNothing) {
  const std::vector<std::string> targets = available_simd_targets();
  ASSERT_EQ("", force_simd_target(targets.back()));
  EXPECT_EQ(
      "SIMD target \"NEON\" is not compiled into this build (choose from " +
          [&] {
            std::string all;
            for (const std::string& t : targets) all += (all.empty() ? "" : ", ") + t;
            return all;
          }() +
          ")",
      force_simd_target("NEON"));
  EXPECT_EQ(targets.back(), active_simd_target());
  ASSERT_EQ("", force_simd_target("ssse3"));  // any case
  EXPECT_EQ("SSSE3", active_simd_target());
  ASSERT_EQ("", force_simd_target(""));
  EXPECT_EQ(targets.front(), active_simd_target());
}

// The two arithmetics agree within 1e-5 of the character's height at every
// vertex of every copy (positions; normals within 1e-5 of unit length), on the
// uneven humanoid whose weights make fused and separate rounding differ.
TEST_F(SimdTargetTest, FusedAndSeparateArithmeticAgreeWithinATolerance) {
  const std::vector<std::string> targets = available_simd_targets();
  if (targets.front().rfind("AVX", 0) != 0) GTEST_SKIP() << "no AVX2 here: one arithmetic only";
  auto skinned = [&](const std::string& target) {
    EXPECT_EQ("", force_simd_target(target));
    CrowdBench bench(uneven_humanoid(), twelve_copies(1, ActionChoice::Random));
    for (int i = 0; i < 3; ++i) bench.step();
    std::vector<glm::vec3> positions, normals;
    for (size_t copy = 0; copy < 12; ++copy) {
      auto p = bench.skinned_positions(copy);
      auto n = bench.skinned_normals(copy);
      positions.insert(positions.end(), p.begin(), p.end());
      normals.insert(normals.end(), n.begin(), n.end());
    }
    return std::pair(positions, normals);
  };
  const auto [fused_p, fused_n] = skinned(targets.front());
  const auto [separate_p, separate_n] = skinned(targets.back());
  ASSERT_EQ(fused_p.size(), separate_p.size());
  const double height = standing_of(uneven_humanoid()).height;
  ASSERT_GT(height, 0.0);
  double worst = 0, worst_normal = 0;
  size_t differing = 0;
  for (size_t v = 0; v < fused_p.size(); ++v) {
    worst = std::max(worst, static_cast<double>(glm::distance(fused_p[v], separate_p[v])));
    worst_normal = std::max(worst_normal, static_cast<double>(glm::distance(fused_n[v], separate_n[v])));
    differing += fused_p[v] != separate_p[v];
  }
  EXPECT_LE(worst, 1e-5 * height);
  EXPECT_LE(worst_normal, 1e-5);
  EXPECT_GT(differing, 0u) << "the arithmetics gave the same bits: is FMA in use?";
}

TEST(SimdCli, OptionAndEnvironmentForceTheTargetAndReportIt) {
  const std::string scene = (test::source_dir() / "scenes/humanoid.glb").string();
  const std::string result_file = (test::scratch_dir("simd_cli") / "run.json").string();
  const std::string lowest = available_simd_targets().back();
  auto r = test::run_cli("--simd " + lowest + " bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" +
                         result_file + "'");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ(lowest, nlohmann::json::parse(std::ifstream(result_file))["environment"]["simd"]);

  r = test::run_cli("--simd " + lowest + " --version");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_NE(std::string::npos, r.out.find(", SIMD " + lowest + ")")) << r.out;

  ASSERT_EQ(0, setenv(kSimdEnvironmentVariable, "SSSE3", 1));
  r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" + result_file + "'");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ("SSSE3", nlohmann::json::parse(std::ifstream(result_file))["environment"]["simd"]);
  r = test::run_cli("--version");
  EXPECT_NE(std::string::npos, r.out.find(", SIMD SSSE3)")) << r.out;
  r = test::run_cli("--simd SSE4 bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" + result_file + "'");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ("SSE4", nlohmann::json::parse(std::ifstream(result_file))["environment"]["simd"]);  // the option wins

  ASSERT_EQ(0, setenv(kSimdEnvironmentVariable, "PENTIUM", 1));
  r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1");
  unsetenv(kSimdEnvironmentVariable);
  EXPECT_EQ(2, r.status);
  EXPECT_NE(std::string::npos,
            r.err.find("crowdprof: the environment's CROWDPROF_SIMD: SIMD target \"PENTIUM\" is not compiled"))
      << r.err;
  EXPECT_EQ(1, std::count(r.err.begin(), r.err.end(), '\n')) << r.err;

  r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" + result_file + "'");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ(active_simd_target(), nlohmann::json::parse(std::ifstream(result_file))["environment"]["simd"]);
}

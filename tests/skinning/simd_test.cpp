// Run-time SIMD dispatch: every target compiled in and runnable here gives the
// same digest at every thread count, and forcing a target works and says why
// it cannot.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "frame/crowd_bench.h"
#include "gen/humanoid.h"
#include "skinning/simd_target.h"
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

std::string digest_of(const Character& character, int threads, ActionChoice actions,
                      VertexFormat format = VertexFormat::Float) {
  BenchConfig config;
  config.mode = find_mode("threaded")->switches;
  config.mode.vertex_format = format;
  config.mode.animation_culling = false;
  config.threads = threads;
  config.crowd.copies = 12;
  config.crowd.actions = actions;
  config.crowd.seed = 5;
  CrowdBench bench(character, config);
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
  // Packed vertices (their bytes are hashed then) too: the codes are rounded
  // from the same floats the same way on every target.
  for (VertexFormat format : {VertexFormat::Float, VertexFormat::Packed}) {
    std::string expected_shared, expected_random;
    for (const std::string& target : targets) {
      ASSERT_EQ("", force_simd_target(target));
      ASSERT_EQ(target, active_simd_target());
      for (int threads : {1, 2, 3}) {
        const std::string shared = digest_of(small_humanoid(), threads, ActionChoice::Shared, format);
        const std::string random = digest_of(uneven_humanoid(), threads, ActionChoice::Random, format);
        if (expected_shared.empty()) expected_shared = shared, expected_random = random;
        EXPECT_EQ(expected_shared, shared) << target << ", " << threads << " threads, " << to_string(format);
        EXPECT_EQ(expected_random, random) << target << ", " << threads << " threads, " << to_string(format);
      }
    }
  }
  EXPECT_NE(digest_of(small_humanoid(), 1, ActionChoice::Shared, VertexFormat::Float),
            digest_of(small_humanoid(), 1, ActionChoice::Shared, VertexFormat::Packed));
}

TEST_F(SimdTargetTest, ForcingAnUnknownTargetChangesNothing) {
  const std::vector<std::string> targets = available_simd_targets();
  ASSERT_EQ("", force_simd_target(targets.back()));
  EXPECT_EQ("SIMD target \"NEON\" is not compiled into this build (choose from " + [&] {
              std::string all;
              for (const std::string& t : targets) all += (all.empty() ? "" : ", ") + t;
              return all;
            }() + ")",
            force_simd_target("NEON"));
  EXPECT_EQ(targets.back(), active_simd_target());
  ASSERT_EQ("", force_simd_target("ssse3"));  // any case
  EXPECT_EQ("SSSE3", active_simd_target());
  ASSERT_EQ("", force_simd_target(""));
  EXPECT_EQ(targets.front(), active_simd_target());
}

TEST(SimdCli, OptionAndEnvironmentForceTheTargetAndReportIt) {
  const std::string scene = (test::source_dir() / "scenes/humanoid.glb").string();
  const std::string json = (test::scratch_dir("simd_cli") / "run.json").string();
  const std::string lowest = available_simd_targets().back();
  auto r = test::run_cli("--simd " + lowest + " bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" + json + "'");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ(lowest, nlohmann::json::parse(std::ifstream(json))["environment"]["simd"]);

  r = test::run_cli("--simd " + lowest + " --version");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_NE(std::string::npos, r.out.find(", SIMD " + lowest + ")")) << r.out;

  ASSERT_EQ(0, setenv(kSimdEnvironmentVariable, "SSSE3", 1));
  r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" + json + "'");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ("SSSE3", nlohmann::json::parse(std::ifstream(json))["environment"]["simd"]);
  r = test::run_cli("--version");
  EXPECT_NE(std::string::npos, r.out.find(", SIMD SSSE3)")) << r.out;
  r = test::run_cli("--simd SSE4 bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" + json + "'");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ("SSE4", nlohmann::json::parse(std::ifstream(json))["environment"]["simd"]);  // the option wins

  ASSERT_EQ(0, setenv(kSimdEnvironmentVariable, "PENTIUM", 1));
  r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1");
  unsetenv(kSimdEnvironmentVariable);
  EXPECT_EQ(2, r.status);
  EXPECT_NE(std::string::npos, r.err.find("crowdprof: SIMD target \"PENTIUM\" is not compiled into this build"))
      << r.err;
  EXPECT_EQ(1, std::count(r.err.begin(), r.err.end(), '\n')) << r.err;

  r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" + json + "'");
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ(active_simd_target(), nlohmann::json::parse(std::ifstream(json))["environment"]["simd"]);
}

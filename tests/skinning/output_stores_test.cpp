// Streaming (non-temporal) stores of skinned vertices: the policy and its rule,
// the same bits as ordinary stores on every SIMD target, whole ranges and
// ranges cut anywhere, and each copy's output on a cache line so that it can
// stream at all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "frame/crowd_bench.h"
#include "gen/humanoid.h"
#include "skinning/output_buffer.h"
#include "skinning/output_stores.h"
#include "skinning/simd_target.h"
#include "skinning/skinning_kernels.h"
#include "skinning/skinning.h"
#include "test_support.h"
#include "characters.h"

using namespace crowdprof;

namespace {

using test::small_humanoid;

BenchConfig threaded(size_t copies, int threads) {
  BenchConfig config;
  config.mode = find_mode("threaded")->switches;
  config.mode.animation_culling = false;
  config.threads = threads;
  config.crowd.copies = copies;
  config.crowd.actions = ActionChoice::Random;
  config.crowd.seed = 3;
  return config;
}

bool on_cache_line(const void* p) {
  return reinterpret_cast<uintptr_t>(p) % 64 == 0;
}

// Puts the policy and the SIMD target back whatever a test forced.
struct OutputStoresTest : ::testing::Test {
  void TearDown() override {
    EXPECT_EQ("", force_output_stores("auto"));
    EXPECT_EQ("", force_simd_target(""));
  }
};

}  // namespace

TEST_F(OutputStoresTest, AutoStreamsOnlyOutputLargerThanTheThreshold) {
  EXPECT_EQ(OutputStores::Auto, output_stores());
  EXPECT_FALSE(stream_skinned_output(0));
  EXPECT_FALSE(stream_skinned_output(kStreamOutputBytes));
  EXPECT_TRUE(stream_skinned_output(kStreamOutputBytes + 1));
  ASSERT_EQ("", force_output_stores("Regular"));  // any case
  EXPECT_EQ(OutputStores::Regular, output_stores());
  EXPECT_FALSE(stream_skinned_output(uint64_t{1} << 40));
  ASSERT_EQ("", force_output_stores("streaming"));
  EXPECT_TRUE(stream_skinned_output(1));
  EXPECT_EQ("unknown store policy \"fast\": expected auto, regular or streaming", force_output_stores("fast"));
  EXPECT_EQ(OutputStores::Streaming, output_stores());  // unchanged
}

TEST_F(OutputStoresTest, BenchStreamsByTheRuleAndEveryCopyStartsOnACacheLine) {
  // 800 vertices, 50 batches: 19,200 bytes a copy, so the rule needs
  // kStreamOutputBytes / 19,200 copies; far fewer stay under it.
  CrowdBench few(small_humanoid(), threaded(7, 1));
  EXPECT_FALSE(few.streams_output());
  ASSERT_EQ("", force_output_stores("streaming"));
  CrowdBench forced(small_humanoid(), threaded(7, 1));
  EXPECT_TRUE(forced.streams_output());
  BenchConfig packed = threaded(7, 1);
  packed.mode.vertex_format = VertexFormat::Packed;
  EXPECT_FALSE(CrowdBench(small_humanoid(), packed).streams_output());  // floats only
  // A mesh whose vertex count is not a whole number of batches: the next copy
  // still starts on a cache line.
  Character odd = generate_humanoid({30, 803, 7});
  ASSERT_NE(0u, odd.mesh.vertex_count() % kSkinBatch) << "pick a humanoid with a partial last batch";
  CrowdBench bench(odd, threaded(5, 1));
  for (size_t copy = 0; copy < 5; ++copy) {
    EXPECT_TRUE(on_cache_line(bench.skinned_positions(copy).data())) << copy;
    EXPECT_TRUE(on_cache_line(bench.skinned_normals(copy).data())) << copy;
    EXPECT_EQ(odd.mesh.vertex_count(), bench.skinned_positions(copy).size());
  }
}

// Every target: streaming and ordinary stores give the same bits, per copy and
// in the digest, at 1 and 2 threads; every target of one arithmetic (fused
// multiply-adds or not) the same digest.
TEST_F(OutputStoresTest, StreamingGivesTheSameBitsOnEveryTarget) {
  std::map<bool, std::string> expected;  // by skinning_fuses_multiply_add()
  for (const std::string& target : available_simd_targets()) {
    ASSERT_EQ("", force_simd_target(target));
    for (int threads : {1, 2}) {
      ASSERT_EQ("", force_output_stores("regular"));
      CrowdBench regular(small_humanoid(), threaded(6, threads));
      ASSERT_EQ("", force_output_stores("streaming"));
      CrowdBench streaming(small_humanoid(), threaded(6, threads));
      ASSERT_FALSE(regular.streams_output());
      ASSERT_TRUE(streaming.streams_output());
      for (int f = 0; f < 3; ++f) regular.step(), streaming.step();
      for (size_t copy = 0; copy < 6; ++copy) {
        auto a = regular.skinned_positions(copy), b = streaming.skinned_positions(copy);
        auto an = regular.skinned_normals(copy), bn = streaming.skinned_normals(copy);
        EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size_bytes())) << target << " copy " << copy;
        EXPECT_EQ(0, std::memcmp(an.data(), bn.data(), an.size_bytes())) << target << " copy " << copy;
      }
      EXPECT_EQ(regular.digest(), streaming.digest()) << target << ", " << threads << " threads";
      std::string& want = expected[skinning_fuses_multiply_add()];
      if (want.empty()) want = regular.digest();
      EXPECT_EQ(want, streaming.digest()) << target << ", " << threads << " threads";
    }
  }
}

// Ranges cut anywhere, into outputs on a cache line or off it: the batches that
// can stream do, the others store as usual, and the bits are the same.
TEST_F(OutputStoresTest, RangesCutAnywhereGiveTheSameBitsStreamed) {
  CrowdBench posed(small_humanoid(), threaded(1, 1));
  posed.step();
  const std::span<const SkinMatrix> palette = posed.skinning_matrices(0);
  SkinningPlan plan;
  const SkinnedMesh& mesh = small_humanoid().mesh;
  ASSERT_EQ("", build_skinning_plan(mesh, palette.size(), &plan));
  const size_t n = mesh.vertex_count();
  std::vector<glm::vec3, CacheLineAllocator<glm::vec3>> want_p(n), want_n(n);
  for (const std::string& target : available_simd_targets()) {
    ASSERT_EQ("", force_simd_target(target));
    ASSERT_TRUE((SkinningJob{palette, &plan, 0, n, want_p, want_n}.Run()));  // whole, not streamed
    for (size_t shift : {0, 1}) {  // output on a cache line, or 12 bytes past one
      for (size_t chunk : {size_t{7}, size_t{16}, size_t{48}, size_t{100}, n}) {
        std::vector<glm::vec3, CacheLineAllocator<glm::vec3>> p(n + shift, glm::vec3(-1)), q(n + shift, glm::vec3(-1));
        for (size_t first = 0; first < n; first += chunk) {
          const size_t count = std::min(chunk, n - first);
          ASSERT_TRUE((SkinningJob{palette, &plan, first, count, std::span(p).subspan(shift + first, count),
                                   std::span(q).subspan(shift + first, count), true}
                           .Run()));
        }
        EXPECT_EQ(0, std::memcmp(p.data() + shift, want_p.data(), n * sizeof(glm::vec3)))
            << target << ", chunks of " << chunk << ", shift " << shift;
        EXPECT_EQ(0, std::memcmp(q.data() + shift, want_n.data(), n * sizeof(glm::vec3)))
            << target << ", chunks of " << chunk << ", shift " << shift;
      }
    }
  }
}

TEST(OutputStoresCli, OptionAndEnvironmentChooseThePolicy) {
  const std::string scene = (test::source_dir() / "scenes/humanoid.glb").string();
  const std::string result_file = (test::scratch_dir("stores_cli") / "run.json").string();
  const std::string run = " bench '" + scene + "' -n 4 --frames 2 --warmup 1 --json '" + result_file + "'";
  auto r = test::run_cli("--stores streaming" + run);
  ASSERT_EQ(0, r.status) << r.err;
  const nlohmann::json streamed = nlohmann::json::parse(std::ifstream(result_file));
  EXPECT_EQ("streaming", streamed["stores"]);
  r = test::run_cli("--stores regular" + run);
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ(streamed["digest"], nlohmann::json::parse(std::ifstream(result_file))["digest"]);
  EXPECT_EQ("regular", nlohmann::json::parse(std::ifstream(result_file))["stores"]);
  ASSERT_EQ(0, setenv(kStoresEnvironmentVariable, "STREAMING", 1));
  r = test::run_cli(run);
  unsetenv(kStoresEnvironmentVariable);
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ("streaming", nlohmann::json::parse(std::ifstream(result_file))["stores"]);
  r = test::run_cli(run);  // auto: 4 copies stay far under the threshold
  ASSERT_EQ(0, r.status) << r.err;
  EXPECT_EQ("regular", nlohmann::json::parse(std::ifstream(result_file))["stores"]);

  ASSERT_EQ(0, setenv(kStoresEnvironmentVariable, "sometimes", 1));
  r = test::run_cli(run);
  unsetenv(kStoresEnvironmentVariable);
  EXPECT_EQ(2, r.status);
  EXPECT_EQ(
      "crowdprof: the environment's CROWDPROF_STORES: unknown store policy \"sometimes\": expected auto, regular or "
      "streaming\n",
      r.err);
  r = test::run_cli("--stores never" + run);
  EXPECT_EQ(2, r.status);
  EXPECT_EQ("crowdprof: unknown store policy \"never\": expected auto, regular or streaming\n", r.err);
}

// Output arrays start on a cache line, large ones on a 2 MiB boundary (where
// Linux can back them with huge pages), and are freed with the same alignment.
TEST(OutputBuffer, SmallOnACacheLineLargeOnAHugePage) {
  for (size_t n : {size_t{1}, size_t{100}, size_t{174'762}}) {
    std::vector<glm::vec3, CacheLineAllocator<glm::vec3>> v(n);
    EXPECT_TRUE(on_cache_line(v.data())) << n;
  }
  for (size_t n : {size_t{174'763}, size_t{1'000'000}}) {  // 2 MiB / 12 bytes and more
    std::vector<glm::vec3, CacheLineAllocator<glm::vec3>> v(n, glm::vec3(1));
    EXPECT_EQ(0u, reinterpret_cast<uintptr_t>(v.data()) % (size_t{2} << 20)) << n;
    EXPECT_EQ(1.0f, v.back().z);
  }
}

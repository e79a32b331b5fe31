// The packed skinned-vertex format (--vertex-format packed): hand-computed
// codes, its stated largest errors, the SIMD kernels against the scalar
// definition on every target, and a crowd's packed vertices against its float
// ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "asset/gltf_loader.h"
#include "frame/crowd_bench.h"
#include "gen/humanoid.h"
#include "skinning/packed_vertex.h"
#include "skinning/simd_target.h"
#include "skinning/skinning.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

double degrees_between(glm::vec3 a, glm::vec3 b) {
  const double c = glm::dot(glm::dvec3(a), glm::dvec3(b)) / (glm::length(glm::dvec3(a)) * glm::length(glm::dvec3(b)));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

}  // namespace

TEST(PackedVertex, HandComputedCodes) {
  // Box (-1, 0, -2)..(1, 2, 2): 2, 2 and 4 units across, 65,535 steps each.
  const PositionQuantisation q = position_quantisation({-1, 0, -2}, {1, 2, 2});
  EXPECT_EQ(32767.5f, q.scale.x);
  EXPECT_EQ(16383.75f, q.scale.z);
  uint16_t code[3];
  // x: 1.5 * 32767.5 = 49151.25 -> 49151; y: the top, 65535; z: the bottom, 0.
  quantise_position(q, {0.5f, 2.0f, -2.0f}, code);
  EXPECT_EQ(49151, code[0]);
  EXPECT_EQ(65535, code[1]);
  EXPECT_EQ(0, code[2]);
  // 0.5 comes back as -1 + 49151 / 65535 * 2 = 0.4999924: 7.6e-6 off, within
  // half a step (2 / 131070 = 1.53e-5).
  EXPECT_NEAR(0.4999924f, dequantise_position(q, code).x, 1e-7f);
  EXPECT_LE(std::abs(dequantise_position(q, code).x - 0.5f), q.max_error().x);
  // Half a step plus 4 ulps of the box's coordinates: 1.53e-5 + 4 x 1.19e-7 x 3.
  EXPECT_NEAR(2.0f / 131070.0f + 4 * 1.1920929e-7f * 3, q.max_error().x, 1e-9f);
  // Ties go to even: y = (1 - 0) * 32767.5 = 32767.5 -> 32768.
  quantise_position(q, {-1.0f, 1.0f, 0.0f}, code);
  EXPECT_EQ(0, code[0]);
  EXPECT_EQ(32768, code[1]);
  EXPECT_EQ(32768, code[2]);  // 2 * 16383.75 = 32767.5 -> 32768
  // Outside the box: clamped to its faces.
  quantise_position(q, {5.0f, -1.0f, 3.0f}, code);
  EXPECT_EQ(65535, code[0]);
  EXPECT_EQ(0, code[1]);
  EXPECT_EQ(65535, code[2]);

  // Normals: x in bits 0-9, y in 10-19, z in 20-29, two's complement, x 511.
  EXPECT_EQ(0x000001ffu, pack_normal({1, 0, 0}));
  EXPECT_EQ(0x00080400u, pack_normal({0, -1, 0}));  // -511 = 0x201 in 10 bits
  EXPECT_EQ(0x1ff00000u, pack_normal({0, 0, 1}));
  // 0.6 * 511 = 306.6 -> 307 = 0x133; -0.8 * 511 = -408.8 -> -409 = 0x267.
  EXPECT_EQ(0x26700133u, pack_normal({0.6f, 0.0f, -0.8f}));
  const glm::vec3 back = unpack_normal(0x26700133u);
  EXPECT_FLOAT_EQ(307.0f / 511.0f, back.x);
  EXPECT_FLOAT_EQ(0.0f, back.y);
  EXPECT_FLOAT_EQ(-409.0f / 511.0f, back.z);
  EXPECT_FLOAT_EQ(-1.0f, unpack_normal(0x200u).x);    // -512 decodes as -1, as GL does
  EXPECT_EQ(0x000001ffu, pack_normal({1.5f, 0, 0}));  // clamped
}

TEST(PackedVertex, LargestErrorsAreAsStated) {
  std::mt19937 rng(3);
  std::normal_distribution<float> gauss;
  double worst_degrees = 0;
  for (int i = 0; i < 500000; ++i) {
    const glm::vec3 n = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)));
    worst_degrees = std::max(worst_degrees, degrees_between(n, unpack_normal(pack_normal(n))));
  }
  std::cout << "[ info ] largest normal error over 500,000 unit normals: " << worst_degrees << " degrees\n";
  EXPECT_LE(worst_degrees, kPackedNormalMaxErrorDegrees);
  EXPECT_GT(worst_degrees, 0.5 * kPackedNormalMaxErrorDegrees);  // the bound is not loose

  const PositionQuantisation q = position_quantisation({-0.61f, -0.03f, -0.42f}, {0.63f, 1.87f, 0.44f});
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  glm::vec3 worst(0.0f);
  for (int i = 0; i < 500000; ++i) {
    const glm::vec3 p = q.min + glm::vec3(u(rng), u(rng), u(rng)) * q.extent;
    uint16_t code[3];
    quantise_position(q, p, code);
    worst = glm::max(worst, glm::abs(dequantise_position(q, code) - p));
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(worst[a], q.max_error()[a]) << a;
    EXPECT_GT(worst[a], 0.9f * q.extent[a] / 131070.0f) << a;
  }
}

namespace {

struct PackedOut {
  std::vector<uint16_t> positions;
  std::vector<uint32_t> normals;
};

// A palette of rotations and translations, with one scaled joint so that both
// kinds of normal (renormalised or kept) are packed.
std::vector<SkinMatrix> random_palette(size_t joints, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<SkinMatrix> palette(joints);
  for (size_t j = 0; j < joints; ++j) {
    glm::quat r = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    palette[j] = glm::translate(glm::mat4(1), glm::vec3(u(rng), u(rng), u(rng)) * 0.2f) * glm::mat4_cast(r);
  }
  palette[joints / 2] = palette[joints / 2] * glm::scale(glm::mat4(1), glm::vec3(1.2f));
  return palette;
}

}  // namespace

TEST(PackedVertex, EveryTargetPacksExactlyWhatTheScalarDefinitionGives) {
  const Character c = generate_humanoid({30, 800, 7});
  const size_t n = c.mesh.vertex_count();
  SkinningPlan plan;
  ASSERT_EQ("", build_skinning_plan(c.mesh, c.skeleton.joint_count(), &plan));
  const std::vector<SkinMatrix> palette = random_palette(c.skeleton.joint_count(), 11);
  std::vector<glm::vec3> positions(n), normals(n);
  ASSERT_TRUE((SkinningJob{palette, &plan, 0, n, positions, normals}.Run()));
  // A box a little smaller than the skinned mesh, so that clamping is tested too.
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 margin = (hi - lo) * 0.02f;
  const PositionQuantisation q = position_quantisation(lo + margin, hi - margin);

  for (const std::string& target : available_simd_targets()) {
    ASSERT_EQ("", force_simd_target(target));
    // The floats this target skins (its arithmetic's last bits: skinning_kernels.h).
    ASSERT_TRUE((SkinningJob{palette, &plan, 0, n, positions, normals}.Run()));
    // The whole mesh, and a range that starts and ends inside batches.
    for (auto [first, count] : {std::pair<size_t, size_t>{0, n}, {5, n - 23}}) {
      PackedOut out{std::vector<uint16_t>(3 * count), std::vector<uint32_t>(count)};
      ASSERT_TRUE((PackedSkinningJob{palette, &plan, &q, first, count, out.positions, out.normals}.Run()));
      size_t wrong = 0, clamped = 0;
      for (size_t i = 0; i < count; ++i) {
        uint16_t code[3];
        quantise_position(q, positions[first + i], code);
        for (int a = 0; a < 3; ++a) {
          wrong += code[a] != out.positions[3 * i + static_cast<size_t>(a)];
          clamped += code[a] == 0 || code[a] == 65535;
        }
        wrong += pack_normal(normals[first + i]) != out.normals[i];
      }
      EXPECT_EQ(0u, wrong) << target << " from " << first;
      EXPECT_GT(clamped, 0u);
    }
  }
  ASSERT_EQ("", force_simd_target(""));
}

TEST(PackedVertex, JobRefusesWrongSizesAndNoBox) {
  const Character c = generate_humanoid({30, 800, 7});
  const size_t n = c.mesh.vertex_count();
  SkinningPlan plan;
  ASSERT_EQ("", build_skinning_plan(c.mesh, c.skeleton.joint_count(), &plan));
  const std::vector<SkinMatrix> palette(c.skeleton.joint_count(), glm::mat4(1));
  const PositionQuantisation q = position_quantisation({-1, -1, -1}, {1, 1, 1});
  std::vector<uint16_t> positions(3 * n);
  std::vector<uint32_t> normals(n);
  EXPECT_TRUE((PackedSkinningJob{palette, &plan, &q, 0, n, positions, normals}.Validate()));
  EXPECT_FALSE((PackedSkinningJob{palette, &plan, nullptr, 0, n, positions, normals}.Validate()));
  EXPECT_FALSE((PackedSkinningJob{palette, &plan, &q, 0, n, std::span(positions).first(n), normals}.Validate()));
  EXPECT_FALSE((PackedSkinningJob{palette, &plan, &q, 1, n, positions, normals}.Run()));
}

// The thesis's character in a crowd, packed against float, frame by frame: the
// decoded positions within the box's stated error, the normals within the
// stated angle; the packed crowd keeps 10 bytes a vertex, not 24.
TEST(PackedVertex, ACrowdsPackedVerticesAreItsFloatVerticesWithinTheStatedError) {
  const Character character = load_character((test::source_dir() / "scenes" / "humanoid.glb").string());
  BenchConfig config;
  config.mode = find_mode("threaded")->switches;
  config.mode.animation_culling = false;
  config.threads = 2;
  config.crowd.copies = 6;
  config.crowd.actions = ActionChoice::Random;
  CrowdBench floats(character, config);
  config.mode.vertex_format = VertexFormat::Packed;
  CrowdBench packed(character, config);
  ASSERT_TRUE(packed.packed_vertices());
  EXPECT_TRUE(packed.skinned_positions(0).empty());
  EXPECT_TRUE(floats.packed_positions(0).empty());
  EXPECT_LT(estimate_bench_bytes(character, 1000, config.mode),
            estimate_bench_bytes(character, 1000, find_mode("threaded")->switches));
  const PositionQuantisation& q = packed.view().characters[0].quantisation;
  glm::vec3 worst(0.0f);
  double worst_degrees = 0;
  for (int frame = 0; frame < 12; ++frame) {
    const Counters a = floats.step().counters, b = packed.step().counters;
    EXPECT_EQ(a.vertices_skinned, b.vertices_skinned);
    for (size_t copy = 0; copy < packed.crowd().size(); ++copy) {
      auto positions = floats.skinned_positions(copy);
      auto normals = floats.skinned_normals(copy);
      auto codes = packed.packed_positions(copy);
      auto words = packed.packed_normals(copy);
      ASSERT_EQ(3 * positions.size(), codes.size());
      for (size_t v = 0; v < positions.size(); ++v) {
        worst = glm::max(worst, glm::abs(dequantise_position(q, &codes[3 * v]) - positions[v]));
        worst_degrees = std::max(worst_degrees, degrees_between(normals[v], unpack_normal(words[v])));
      }
    }
  }
  float low = 1e9f, high = -1e9f;  // the character's height at rest
  for (const glm::vec3& p : character.mesh.positions) low = std::min(low, p.y), high = std::max(high, p.y);
  const float height = high - low;
  std::cout << "[ info ] humanoid box " << q.extent.x << " x " << q.extent.y << " x " << q.extent.z
            << "; largest position error " << worst.x << ", " << worst.y << ", " << worst.z << " (bound "
            << q.max_error().x << ", " << q.max_error().y << ", " << q.max_error().z << "), "
            << std::max({worst.x, worst.y, worst.z}) / height << " of the character's height " << height
            << "; largest normal error " << worst_degrees << " degrees\n";
  for (int a = 0; a < 3; ++a) EXPECT_LE(worst[a], q.max_error()[a]) << a;
  EXPECT_LE(worst_degrees, kPackedNormalMaxErrorDegrees);
  EXPECT_NE(floats.digest(), packed.digest());
}

TEST(PackedVertex, TheSwitchIsRecordedOnlyWhenPackedAndBadValuesAreRefused) {
  const std::string scene = (test::source_dir() / "scenes/humanoid.glb").string();
  const std::string result_file = (test::scratch_dir("packed_cli") / "run.json").string();
  auto r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1 --vertex-format packed --json '" +
                         result_file + "'");
  ASSERT_EQ(0, r.status) << r.err;
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(result_file));
  EXPECT_EQ("packed", doc["switches"]["vertex_format"]);
  EXPECT_EQ("threaded+custom", doc["mode"]);
  const std::string packed_digest = doc["digest"];
  r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1 --vertex-format float --json '" + result_file +
                    "'");
  ASSERT_EQ(0, r.status) << r.err;
  doc = nlohmann::json::parse(std::ifstream(result_file));
  EXPECT_FALSE(doc["switches"].contains("vertex_format"));
  EXPECT_EQ("threaded", doc["mode"]);
  EXPECT_NE(packed_digest, doc["digest"]);
  r = test::run_cli("bench '" + scene + "' -n 4 --frames 2 --warmup 1 --vertex-format half");
  EXPECT_EQ(2, r.status);
  EXPECT_EQ("crowdprof: bench: --vertex-format 'half': expected one of float, packed (see crowdprof bench --help)\n",
            r.err);
}

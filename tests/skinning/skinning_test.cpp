// Software skinning: the thesis's worked example, 1 to 4 influences against a
// straightforward reference, and the same bits however the mesh is split.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <cstring>
#include <limits>
#include <map>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "skinning/simd_target.h"
#include "skinning/skinning.h"
#include "skinning/skinning_kernels.h"
#include "skinning/skinning_plan.h"

namespace crowdprof {
namespace {

struct Skinned {
  std::vector<glm::vec3> positions, normals;
};

SkinningPlan plan_of(const SkinnedMesh& mesh, size_t joints) {
  SkinningPlan plan;
  EXPECT_EQ("", build_skinning_plan(mesh, joints, &plan));
  return plan;
}

Skinned skin(const SkinnedMesh& mesh, const std::vector<SkinMatrix>& palette) {
  Skinned out;
  out.positions.resize(mesh.vertex_count());
  out.normals.resize(mesh.vertex_count());
  const SkinningPlan plan = plan_of(mesh, palette.size());
  EXPECT_TRUE((SkinningJob{palette, &plan, 0, mesh.vertex_count(), out.positions, out.normals}.Run()));
  return out;
}

void add_vertex(SkinnedMesh* mesh, glm::vec3 position, glm::vec3 normal, glm::u16vec4 joints, glm::vec4 weights) {
  mesh->positions.push_back(position);
  mesh->normals.push_back(normal);
  mesh->joints.push_back(joints);
  mesh->weights.push_back(weights);
}

TEST(Skinning, ThesisWorkedExample) {
  // Thesis §2.2, equation 3: a vertex at (0, 0, 1) weighted 0.5/0.5 to two bones,
  // one at rest (identity), one rotated 45 degrees (here about x). The blend gives
  // z = 0.5 * 1 + 0.5 * cos 45 = 0.5 + 0.5 * 0.70711 = 0.85355. The thesis prints
  // 0.85255, an arithmetic slip: the correct value is tested.
  SkinnedMesh mesh;
  add_vertex(&mesh, {0, 0, 1}, {0, 0, 1}, {0, 1, 0, 0}, {0.5f, 0.5f, 0, 0});
  const std::vector<SkinMatrix> palette = {glm::mat4(1),
                                           glm::rotate(glm::mat4(1), glm::radians(45.0f), glm::vec3(1, 0, 0))};
  const Skinned out = skin(mesh, palette);
  EXPECT_NEAR(out.positions[0].z, 0.85355339f, 1e-6f);
  EXPECT_NEAR(out.positions[0].y, -0.35355339f, 1e-6f);  // 0.5 * -sin 45
  EXPECT_NEAR(out.positions[0].x, 0.0f, 1e-6f);
  // The normal blends the same way, then is re-normalised: 22.5 degrees from z.
  EXPECT_NEAR(out.normals[0].z, std::cos(glm::radians(22.5f)), 1e-6f);
  EXPECT_NEAR(out.normals[0].y, -std::sin(glm::radians(22.5f)), 1e-6f);
}

// sum_i w_i (M_i p) in double: equation 1 without any cleverness.
glm::dvec3 reference_point(const std::vector<SkinMatrix>& palette, glm::u16vec4 j, glm::vec4 w, glm::vec3 p, double h) {
  glm::dvec4 sum(0.0);
  for (int k = 0; k < 4; ++k) sum += double(w[k]) * (glm::dmat4(palette[j[k]]) * glm::dvec4(p, h));
  return glm::dvec3(sum);
}

SkinnedMesh random_mesh(size_t vertices, int joints, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::uniform_int_distribution<int> joint(0, joints - 1), influences(1, 4);
  SkinnedMesh mesh;
  for (size_t v = 0; v < vertices; ++v) {
    const int n = influences(*rng);
    std::array<float, 4> weights{};  // sorted largest first, as the mesh keeps them
    glm::u16vec4 j(0);
    for (int k = 0; k < n; ++k) {
      weights[k] = 0.1f + std::abs(u(*rng));
      j[k] = static_cast<uint16_t>(joint(*rng));
    }
    std::sort(weights.begin(), weights.end(), std::greater<float>());
    glm::vec4 w(weights[0], weights[1], weights[2], weights[3]);
    w /= w.x + w.y + w.z + w.w;
    add_vertex(&mesh, {u(*rng) * 2, u(*rng) * 2, u(*rng) * 2},
               glm::normalize(glm::vec3(u(*rng), u(*rng), u(*rng)) + glm::vec3(0.01f)), j, w);
  }
  return mesh;
}

std::vector<SkinMatrix> random_palette(int joints, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<SkinMatrix> palette;
  for (int j = 0; j < joints; ++j) {
    glm::mat4 m = glm::mat4_cast(glm::normalize(glm::quat(u(*rng), u(*rng), u(*rng), u(*rng))));
    m = glm::scale(m, glm::vec3(0.8f + 0.4f * std::abs(u(*rng))));
    m[3] = glm::vec4(u(*rng) * 3, u(*rng) * 3, u(*rng) * 3, 1.0f);
    palette.push_back(m);
  }
  return palette;
}

TEST(Skinning, OneToFourInfluencesMatchTheReference) {
  std::mt19937 rng(11);
  const SkinnedMesh mesh = random_mesh(1000, 20, &rng);
  const std::vector<SkinMatrix> palette = random_palette(20, &rng);
  const Skinned out = skin(mesh, palette);
  int seen[5] = {};
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const glm::vec4 w = mesh.weights[v];
    seen[(w.x != 0) + (w.y != 0) + (w.z != 0) + (w.w != 0)]++;
    const glm::dvec3 p = reference_point(palette, mesh.joints[v], w, mesh.positions[v], 1.0);
    const glm::dvec3 n = glm::normalize(reference_point(palette, mesh.joints[v], w, mesh.normals[v], 0.0));
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(out.positions[v][k], p[k], 1e-5) << "vertex " << v;
      ASSERT_NEAR(out.normals[v][k], n[k], 1e-5) << "vertex " << v;
    }
  }
  for (int n = 1; n <= 4; ++n) EXPECT_GT(seen[n], 100) << n << " influences";
}

TEST(Skinning, ZeroWeightsAreSkipped) {
  // Joint 1's matrix is NaN: a weight of 0 must not multiply it in (0 * NaN is NaN).
  SkinnedMesh mesh;
  add_vertex(&mesh, {1, 2, 3}, {0, 1, 0}, {0, 1, 1, 1}, {1, 0, 0, 0});
  add_vertex(&mesh, {1, 2, 3}, {0, 1, 0}, {2, 0, 1, 1}, {0.5f, 0.5f, 0, 0});
  std::vector<SkinMatrix> palette = {glm::translate(glm::mat4(1), glm::vec3(1, 0, 0)),
                                     glm::mat4(std::numeric_limits<float>::quiet_NaN()),
                                     glm::translate(glm::mat4(1), glm::vec3(0, 0, 1))};
  const Skinned out = skin(mesh, palette);
  EXPECT_EQ(out.positions[0], glm::vec3(2, 2, 3));
  EXPECT_EQ(out.positions[1], glm::vec3(1.5f, 2, 3.5f));
  EXPECT_EQ(out.normals[0], glm::vec3(0, 1, 0));
}

TEST(Skinning, NormalThatBlendsToNothingComesOutZero) {
  // Half at rest, half turned 180 degrees about y: the normal (0,0,1) cancels.
  SkinnedMesh mesh;
  add_vertex(&mesh, {0, 0, 1}, {0, 0, 1}, {0, 1, 0, 0}, {0.5f, 0.5f, 0, 0});
  const std::vector<SkinMatrix> palette = {glm::mat4(1),
                                           glm::scale(glm::mat4(1), glm::vec3(-1, 1, -1))};  // exactly 180 degrees
  const Skinned out = skin(mesh, palette);
  EXPECT_EQ(out.positions[0], glm::vec3(0));
  EXPECT_FALSE(std::isnan(out.normals[0].x) || std::isnan(out.normals[0].y) || std::isnan(out.normals[0].z));
  EXPECT_EQ(glm::length(out.normals[0]), 0.0f);
}

TEST(Skinning, AnySplitIntoRangesGivesTheSameBits) {
  std::mt19937 rng(5);
  const SkinnedMesh mesh = random_mesh(517, 30, &rng);
  const std::vector<SkinMatrix> palette = random_palette(30, &rng);
  const Skinned whole = skin(mesh, palette);
  const SkinningPlan plan = plan_of(mesh, palette.size());
  for (size_t chunk : {1, 3, 15, 16, 17, 63, 64, 65, 100, 516}) {
    Skinned parts;
    parts.positions.assign(mesh.vertex_count(), glm::vec3(-1));
    parts.normals.assign(mesh.vertex_count(), glm::vec3(-1));
    for (size_t first = 0; first < mesh.vertex_count(); first += chunk) {
      const size_t count = std::min(chunk, mesh.vertex_count() - first);
      ASSERT_TRUE((SkinningJob{palette, &plan, first, count, std::span(parts.positions).subspan(first, count),
                               std::span(parts.normals).subspan(first, count)}
                       .Run()));
    }
    EXPECT_EQ(0,
              std::memcmp(parts.positions.data(), whole.positions.data(), whole.positions.size() * sizeof(glm::vec3)))
        << "chunks of " << chunk;
    EXPECT_EQ(0, std::memcmp(parts.normals.data(), whole.normals.data(), whole.normals.size() * sizeof(glm::vec3)))
        << "chunks of " << chunk;
  }
}

// Puts the CPU's best target back whatever a test forced, even when it fails.
struct SkinningOnEveryTarget : ::testing::Test {
  void TearDown() override { EXPECT_EQ("", force_simd_target("")); }
};

TEST_F(SkinningOnEveryTarget, SkeletonsBelowAtAndAboveTheTableLimitInTurn) {
  // SSE4 and SSSE3 broadcast the palette into a table on the kernel's stack,
  // filled each call, for skeletons of up to 128 joints, and broadcast from
  // the palette above that. One thread skins 4 joints, 128 (the last one used),
  // 300, then the 4 with a new palette, which a table not filled afresh gets
  // wrong. Every target gives its arithmetic's bits (the first target of each
  // is the reference) and stays within 1e-5 of equation 1 in double. A table
  // too small for joint 127 writes past it on the stack: AddressSanitizer's
  // stage of CI catches that.
  std::mt19937 rng(23);
  const SkinnedMesh small = random_mesh(200, 4, &rng), bound = random_mesh(600, 128, &rng),
                    large = random_mesh(500, 300, &rng);
  ASSERT_EQ(127, plan_of(bound, 128).skin_joints.back());
  const std::vector<std::pair<const SkinnedMesh*, std::vector<SkinMatrix>>> runs = {{&small, random_palette(4, &rng)},
                                                                                    {&bound, random_palette(128, &rng)},
                                                                                    {&large, random_palette(300, &rng)},
                                                                                    {&small, random_palette(4, &rng)}};
  std::map<bool, std::vector<Skinned>> by_arithmetic;
  for (const std::string& target : available_simd_targets()) {
    ASSERT_EQ("", force_simd_target(target));
    std::vector<Skinned> got;
    for (const auto& [mesh, palette] : runs) {
      got.push_back(skin(*mesh, palette));
      for (size_t v = 0; v < mesh->vertex_count(); ++v) {
        const glm::dvec3 p = reference_point(palette, mesh->joints[v], mesh->weights[v], mesh->positions[v], 1.0);
        for (int k = 0; k < 3; ++k) ASSERT_NEAR(got.back().positions[v][k], p[k], 1e-5) << target << " vertex " << v;
      }
    }
    const auto [reference, is_reference] = by_arithmetic.try_emplace(skinning_fuses_multiply_add(), got);
    if (is_reference) continue;
    for (size_t r = 0; r < runs.size(); ++r) {
      const size_t bytes = runs[r].first->vertex_count() * sizeof(glm::vec3);
      EXPECT_EQ(0, std::memcmp(got[r].positions.data(), reference->second[r].positions.data(), bytes))
          << target << " run " << r;
      EXPECT_EQ(0, std::memcmp(got[r].normals.data(), reference->second[r].normals.data(), bytes))
          << target << " run " << r;
    }
  }
}

TEST(Skinning, ValidateRefusesBadRanges) {
  std::mt19937 rng(9);
  SkinnedMesh mesh = random_mesh(10, 4, &rng);
  mesh.joints[0].x = 3;  // the palette's last joint is used
  const std::vector<SkinMatrix> palette = random_palette(4, &rng);
  const SkinningPlan plan = plan_of(mesh, 4);
  std::vector<glm::vec3> p(10), n(10);
  const std::span<glm::vec3> ps(p), ns(n);
  EXPECT_TRUE((SkinningJob{palette, &plan, 0, 10, ps, ns}.Run()));
  EXPECT_TRUE((SkinningJob{palette, &plan, 4, 6, ps.subspan(4), ns.subspan(4)}.Run()));
  EXPECT_TRUE((SkinningJob{palette, &plan, 10, 0, {}, {}}.Run()));
  EXPECT_FALSE((SkinningJob{palette, &plan, 4, 7, ps.subspan(3), ns.subspan(3)}.Run()));  // past the end
  EXPECT_FALSE((SkinningJob{palette, &plan, 4, 6, ps, ns}.Run()));  // outputs not sized to the range
  EXPECT_FALSE((SkinningJob{palette, nullptr, 0, 10, ps, ns}.Run()));
  EXPECT_FALSE((SkinningJob{std::span(palette).first(3), &plan, 0, 10, ps, ns}.Run()));  // palette too short
}

TEST(SkinningPlan, RefusesJointIndicesPastTheSkeletonAndUnevenArrays) {
  std::mt19937 rng(9);
  SkinnedMesh mesh = random_mesh(40, 4, &rng);
  SkinningPlan plan;
  EXPECT_EQ("", build_skinning_plan(mesh, 4, &plan));
  mesh.joints[37].w = 4;  // one past the skeleton, even with weight 0
  EXPECT_EQ("vertex 37 uses joint 4 of 4", build_skinning_plan(mesh, 4, &plan));
  EXPECT_EQ(0u, plan.vertex_count);
  EXPECT_EQ("", build_skinning_plan(mesh, 5, &plan));
  mesh.normals.pop_back();
  EXPECT_NE("", build_skinning_plan(mesh, 5, &plan));
}

TEST(SkinningPlan, BatchesHoldTheUnionOfTheirJointsWithNonZeroWeight) {
  SkinnedMesh mesh;
  for (int v = 0; v < 20; ++v)  // 16 in the first batch, 4 in the second
    add_vertex(&mesh, glm::vec3(float(v)), {0, 0, 1}, {uint16_t(v < 16 ? 5 : 2), 7, 3, 0},
               v == 3 ? glm::vec4(0.5f, 0.5f, 0, 0) : glm::vec4(1, 0, 0, 0));
  const SkinningPlan plan = plan_of(mesh, 8);
  ASSERT_EQ(2u, plan.batch_count());
  const SkinBatch& first = plan.batches[0];
  EXPECT_EQ(std::vector<uint16_t>({5, 7}),
            std::vector<uint16_t>(plan.joints.begin() + first.first_joint,
                                  plan.joints.begin() + first.first_joint + first.joint_count));
  EXPECT_EQ(0, first.single_influence);  // vertex 3 has two influences
  const SkinBatch& second = plan.batches[1];
  EXPECT_EQ(1, second.joint_count);
  EXPECT_EQ(2, plan.joints[second.first_joint]);
  EXPECT_EQ(1, second.single_influence);
  EXPECT_EQ(std::vector<uint16_t>({2}), plan.single_joints);
  EXPECT_EQ(std::vector<uint16_t>({2, 5, 7}), plan.skin_joints);  // 0 and 3 weigh 0 everywhere
  // Rows: x, y, z, normal x, y, z, then one weight row per joint; padding lanes 0.
  const float* rows = plan.data.data() + second.data;
  EXPECT_EQ(19.0f, rows[3]);
  EXPECT_EQ(0.0f, rows[4]);
  EXPECT_EQ(1.0f, rows[6 * kSkinBatch + 3]);
  EXPECT_EQ(0.0f, rows[6 * kSkinBatch + 4]);
  const float* first_rows = plan.data.data() + first.data;
  EXPECT_EQ(0.5f, first_rows[6 * kSkinBatch + 3]);
  EXPECT_EQ(0.5f, first_rows[7 * kSkinBatch + 3]);
  EXPECT_EQ(1.0f, first_rows[6 * kSkinBatch + 2]);
  EXPECT_EQ(0.0f, first_rows[7 * kSkinBatch + 2]);
}

// Single-influence normals are renormalised unless every such joint is a
// rotation: with a scaled joint they come out unit length anyway, and with a
// rotation they come out as rotated, bit for bit the plain matrix product.
TEST(Skinning, SingleInfluenceNormalsKeepTheirLengthOnlyUnderRotations) {
  SkinnedMesh mesh;
  const glm::vec3 normal = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  for (int v = 0; v < 16; ++v) add_vertex(&mesh, {1, 2, 3}, normal, {1, 0, 0, 0}, {1, 0, 0, 0});
  const glm::mat4 rotation = glm::rotate(glm::mat4(1), 0.7f, glm::normalize(glm::vec3(1, 2, 3)));
  ASSERT_TRUE(is_rigid(rotation));
  Skinned out = skin(mesh, {glm::mat4(1), rotation});
  const glm::vec3 rotated = glm::vec3(rotation * glm::vec4(normal, 0.0f));
  EXPECT_NEAR(glm::length(out.normals[5]), 1.0f, 1.5e-5f);
  // Exactly the rotated normal (terms added in the kernel's order, fused where
  // the kernel fuses), not renormalised.
  glm::vec3 expected;
  for (int a = 0; a < 3; ++a) {
    const float x = rotation[0][a] * normal.x;
    expected[a] = skinning_fuses_multiply_add()
                      ? std::fma(rotation[2][a], normal.z, std::fma(rotation[1][a], normal.y, x))
                      : (x + rotation[1][a] * normal.y) + rotation[2][a] * normal.z;
  }
  EXPECT_EQ(expected, out.normals[5]);
  EXPECT_NEAR(glm::distance(rotated, out.normals[5]), 0.0f, 1e-6f);

  const glm::mat4 scaled = glm::scale(rotation, glm::vec3(1.5f));
  ASSERT_FALSE(is_rigid(scaled));
  out = skin(mesh, {glm::mat4(1), scaled});
  EXPECT_NEAR(glm::length(out.normals[5]), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(rotated, out.normals[5]), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace crowdprof

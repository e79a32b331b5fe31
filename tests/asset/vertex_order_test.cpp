// Vertices ordered for skinning (lib/asset/vertex_order.h): each primitive's
// vertices sorted by their joints, the same triangles, and the same skinned
// vertex wherever a vertex lands; fewer joints blended a batch. A bench's
// characters and the mesh levels come ordered.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "asset/asset_report.h"
#include "asset/mesh_lod.h"
#include "asset/vertex_order.h"
#include "frame/bench_setup.h"
#include "render_support.h"
#include "skinning/skinning.h"
#include "skinning/skinning_plan.h"

namespace crowdprof {
namespace {

// A vertex's joints of non-zero weight, ascending, padded past any joint (as
// the library compares them: {1, 3, 5} before {1, 3}).
std::array<int, 4> joint_set(const SkinnedMesh& m, size_t v) {
  std::array<int, 4> set{1 << 20, 1 << 20, 1 << 20, 1 << 20};
  size_t used = 0;
  for (int k = 0; k < 4; ++k) {
    if (m.weights[v][k] == 0.0f) continue;
    size_t at = used++;  // insertion: GCC 12 warns falsely on std::sort of a few
    for (; at > 0 && set[at - 1] > m.joints[v][k]; --at) set[at] = set[at - 1];
    set[at] = m.joints[v][k];
  }
  return set;
}

// Every primitive's vertices in ascending joint sets.
bool ordered_by_joints(const SkinnedMesh& m) {
  for (const Primitive& p : m.primitives)
    for (size_t v = p.first_vertex + 1; v < p.first_vertex + p.vertex_count; ++v)
      if (joint_set(m, v) < joint_set(m, v - 1)) return false;
  return true;
}

// Two primitives, of four vertices and of three; vertex v sits at (v, 0, 0)
// with a normal of its own.
SkinnedMesh two_primitives() {
  SkinnedMesh m;
  const glm::u16vec4 joints[7] = {{3, 0, 0, 0}, {1, 3, 0, 0}, {2, 0, 0, 0}, {3, 1, 0, 0},
                                  {5, 0, 0, 0}, {0, 0, 0, 0}, {4, 5, 0, 0}};
  const glm::vec4 weights[7] = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0},      {0.7f, 0.3f, 0, 0},
                                {1, 0, 0, 0}, {1, 0, 0, 0},       {0.6f, 0.4f, 0, 0}};
  for (int v = 0; v < 7; ++v) {
    m.positions.push_back({float(v), 0, 0});
    m.normals.push_back(glm::normalize(glm::vec3(0, 0.1f * float(v), 1)));
    m.joints.push_back(joints[v]);
    m.weights.push_back(weights[v]);
  }
  m.indices = {0, 1, 2, 2, 3, 0, 4, 5, 6};
  m.primitives = {{0, 6, 0, 4}, {6, 3, 4, 3}};
  return m;
}

TEST(VertexOrder, EachPrimitiveIsSortedByItsJointsAndDrawsTheSameTriangles) {
  const SkinnedMesh before = two_primitives();
  SkinnedMesh after = before;
  const std::vector<uint32_t> old_of_new = order_vertices_by_joints(after);
  // {1,3} {1,3} (the file's order kept within a set) {2} {3}; then {0} {4,5} {5}.
  // Not its own inverse, so new and old numbers swapped would show.
  EXPECT_EQ(old_of_new, (std::vector<uint32_t>{1, 3, 2, 0, 5, 6, 4}));
  for (size_t v = 0; v < before.vertex_count(); ++v) {
    EXPECT_EQ(after.positions[v], before.positions[old_of_new[v]]);
    EXPECT_EQ(after.normals[v], before.normals[old_of_new[v]]);
    EXPECT_EQ(after.joints[v], before.joints[old_of_new[v]]);
    EXPECT_EQ(after.weights[v], before.weights[old_of_new[v]]);
  }
  ASSERT_EQ(after.indices.size(), before.indices.size());
  for (size_t i = 0; i < after.indices.size(); ++i)
    EXPECT_EQ(after.positions[after.indices[i]], before.positions[before.indices[i]]) << "index " << i;
  EXPECT_TRUE(ordered_by_joints(after));
  // Ordered already: nothing moves.
  SkinnedMesh again = after;
  EXPECT_EQ(order_vertices_by_joints(again), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(again.indices, after.indices);
}

TEST(VertexOrder, PrimitivesThatOverlapOrLeaveVerticesOutAreLeftAsTheyAre) {
  for (int broken = 0; broken < 4; ++broken) {
    SkinnedMesh m = two_primitives();
    if (broken == 0) m.primitives[1].first_vertex = 3;  // overlaps the first
    if (broken == 1) m.primitives[1].vertex_count = 2;  // vertex 6 in none
    if (broken == 2) m.primitives[1].vertex_count = 9;  // past the arrays
    if (broken == 3) m.primitives.clear();              // vertices in none
    const SkinnedMesh before = m;
    EXPECT_EQ(order_vertices_by_joints(m), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6})) << broken;
    EXPECT_EQ(m.joints, before.joints) << broken;
    EXPECT_EQ(m.indices, before.indices) << broken;
  }
}

size_t joints_blended(const SkinnedMesh& mesh, size_t joint_count) {
  SkinningPlan plan;
  EXPECT_EQ(build_skinning_plan(mesh, joint_count, &plan), "");
  size_t joints = 0;
  for (const SkinBatch& batch : plan.batches) joints += batch.joint_count;
  return joints;
}

TEST(VertexOrder, TheHumanoidBlendsFewerJointsAndSkinsEveryVertexAlike) {
  const Character& humanoid = test::default_humanoid();
  const SkinnedMesh& before = humanoid.mesh;
  SkinnedMesh after = before;
  const std::vector<uint32_t> old_of_new = order_vertices_by_joints(after);
  const size_t joints = humanoid.skeleton.joint_count();
  // 3.06 joints a batch in the file's order, 2.64 in this one.
  EXPECT_LT(joints_blended(after, joints) * 100, joints_blended(before, joints) * 90);
  for (size_t i = 0; i < after.indices.size(); ++i)
    ASSERT_EQ(after.positions[after.indices[i]], before.positions[before.indices[i]]) << "index " << i;

  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<SkinMatrix> palette;
  for (size_t j = 0; j < joints; ++j) {
    glm::mat4 m = glm::mat4_cast(glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng))));
    m[3] = glm::vec4(u(rng), u(rng), u(rng), 1.0f);
    palette.push_back(m);
  }
  const size_t n = before.vertex_count();
  std::vector<glm::vec3> p0(n), n0(n), p1(n), n1(n);
  SkinningPlan plan0, plan1;
  ASSERT_EQ(build_skinning_plan(before, joints, &plan0), "");
  ASSERT_EQ(build_skinning_plan(after, joints, &plan1), "");
  ASSERT_TRUE((SkinningJob{palette, &plan0, 0, n, p0, n0}.Run()));
  ASSERT_TRUE((SkinningJob{palette, &plan1, 0, n, p1, n1}.Run()));
  // Positions exactly: a joint a vertex does not weigh adds a zero, and the
  // ones it does are summed in the same (ascending) order in any batch.
  // Normals within rounding: a vertex may land in a batch of single-influence
  // vertices, whose rotated unit normals are not renormalised.
  size_t moved = 0;
  for (size_t v = 0; v < n; ++v) {
    ASSERT_EQ(p1[v], p0[old_of_new[v]]) << "vertex " << v;
    ASSERT_LT(glm::length(n1[v] - n0[old_of_new[v]]), 1e-6f) << "vertex " << v;
    moved += old_of_new[v] != v;
  }
  EXPECT_GT(moved, n / 2);
}

TEST(VertexOrder, ABenchsCharacterAndItsMeshLevelsComeOrdered) {
  RunSpec spec;
  spec.file = (test::source_dir() / "scenes" / "humanoid.glb").string();
  const BenchScene scene = load_bench_scene(spec);
  const Character& loaded = test::default_humanoid();  // the file's order
  ASSERT_FALSE(ordered_by_joints(loaded.mesh));
  EXPECT_TRUE(ordered_by_joints(scene.first().mesh));
  const std::vector<MeshLod> levels = mesh_lods_of(scene.first());
  ASSERT_FALSE(levels.empty());
  for (const MeshLod& level : levels) EXPECT_TRUE(ordered_by_joints(level.mesh));
  // The same levels whether the character came ordered or not (meshoptimizer
  // breaks ties by vertex index): what `info` says is what a bench draws.
  const std::vector<MeshLod> file_levels = mesh_lods_of(loaded);
  ASSERT_EQ(file_levels.size(), levels.size());
  for (size_t l = 0; l < levels.size(); ++l) {
    EXPECT_EQ(file_levels[l].mesh.indices, levels[l].mesh.indices) << l;
    EXPECT_EQ(file_levels[l].mesh.positions, levels[l].mesh.positions) << l;
    EXPECT_EQ(file_levels[l].error, levels[l].error) << l;
  }
}

// info's vertex cache figures: per primitive and mesh level, each model by its
// parameters, file order against vertex-cache order. On the humanoid as it
// comes the optimized order shades fewer vertices under every model, and the
// mesh levels, built in cache order, gain nothing from it.
TEST(VertexOrder, InfoGivesVertexCacheFiguresInBothOrders) {
  const nlohmann::json info = describe_asset(load_gltf((test::source_dir() / "scenes" / "humanoid.glb").string()));
  const nlohmann::json& parts = info["characters"][0]["vertex_cache"];
  ASSERT_EQ(parts.size(), 1 + info["characters"][0]["mesh_lods"].size()) << "the primitive, then each level";
  ASSERT_EQ(parts[0]["primitive"], 0);
  ASSERT_EQ(parts[0]["models"].size(), std::size(kVertexCacheModels));
  const nlohmann::json& nvidia = parts[0]["models"][0];
  EXPECT_EQ(nvidia["model"], "NVIDIA-like");
  EXPECT_EQ(nvidia["cache_size"], 32);
  for (const nlohmann::json& m : parts[0]["models"]) {
    EXPECT_LT(m["optimized"]["atvr"].get<double>(), m["file"]["atvr"].get<double>()) << m["model"];
    EXPECT_GE(m["optimized"]["atvr"].get<double>(), 1.0) << m["model"] << ": each vertex shaded at least once";
    EXPECT_NEAR(m["file"]["acmr"].get<double>() * 9818 / 4951, m["file"]["atvr"].get<double>(), 1e-6)
        << "every vertex of the humanoid is used: ATVR is ACMR times triangles over vertices";
  }
  for (size_t l = 1; l < parts.size(); ++l) {
    EXPECT_EQ(parts[l]["level"], l);
    const nlohmann::json& m = parts[l]["models"][0];
    EXPECT_NEAR(m["optimized"]["atvr"].get<double>(), m["file"]["atvr"].get<double>(), 0.02) << l;
  }
}

}  // namespace
}  // namespace crowdprof

// Vertices ordered for skinning (lib/asset/vertex_order.h): each primitive's
// vertices sorted by their joints, the same triangles, and the same skinned
// vertex wherever a vertex lands; fewer joints blended a batch.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "asset/vertex_order.h"
#include "render_support.h"
#include "skinning/skinning.h"
#include "skinning/skinning_plan.h"

namespace crowdprof {
namespace {

// Two primitives of three vertices each; vertex v sits at (v, 0, 0).
SkinnedMesh two_primitives() {
  SkinnedMesh m;
  const glm::u16vec4 joints[6] = {{3, 1, 0, 0}, {2, 0, 0, 0}, {1, 3, 0, 0}, {5, 0, 0, 0}, {4, 5, 0, 0}, {0, 0, 0, 0}};
  const glm::vec4 weights[6] = {{0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}, {0.7f, 0.3f, 0, 0},
                                {1, 0, 0, 0},       {0.6f, 0.4f, 0, 0}, {1, 0, 0, 0}};
  for (int v = 0; v < 6; ++v) {
    m.positions.push_back({float(v), 0, 0});
    m.normals.push_back({0, 0, 1});
    m.joints.push_back(joints[v]);
    m.weights.push_back(weights[v]);
  }
  m.indices = {0, 1, 2, 2, 1, 0, 3, 4, 5};
  m.primitives = {{0, 6, 0, 3}, {6, 3, 3, 3}};
  return m;
}

TEST(VertexOrder, EachPrimitiveIsSortedByItsJointsAndDrawsTheSameTriangles) {
  const SkinnedMesh before = two_primitives();
  SkinnedMesh after = before;
  const std::vector<uint32_t> old_of_new = order_vertices_by_joints(after);
  // {1,3} {1,3} {2} in the first range (file order kept within a set), {0} {4,5} {5} in the second.
  EXPECT_EQ(old_of_new, (std::vector<uint32_t>{0, 2, 1, 5, 4, 3}));
  for (size_t v = 0; v < 6; ++v) {
    EXPECT_EQ(after.positions[v], before.positions[old_of_new[v]]);
    EXPECT_EQ(after.joints[v], before.joints[old_of_new[v]]);
    EXPECT_EQ(after.weights[v], before.weights[old_of_new[v]]);
  }
  ASSERT_EQ(after.indices.size(), before.indices.size());
  for (size_t i = 0; i < after.indices.size(); ++i)
    EXPECT_EQ(after.positions[after.indices[i]], before.positions[before.indices[i]]) << "index " << i;
  EXPECT_EQ(after.primitives.size(), before.primitives.size());
}

TEST(VertexOrder, PrimitivesThatOverlapOrLeaveVerticesOutAreLeftAsTheyAre) {
  for (int broken = 0; broken < 3; ++broken) {
    SkinnedMesh m = two_primitives();
    if (broken == 0) m.primitives[1].first_vertex = 2;  // overlaps the first
    if (broken == 1) m.primitives[1].vertex_count = 2;  // vertex 5 in none
    if (broken == 2) m.primitives[1].vertex_count = 9;  // past the arrays
    const SkinnedMesh before = m;
    EXPECT_EQ(order_vertices_by_joints(m), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5})) << broken;
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

}  // namespace
}  // namespace crowdprof

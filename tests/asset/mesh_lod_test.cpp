// Mesh LOD levels (lib/asset/mesh_lod.h): at least three coarser levels of the
// thesis's character, each a subset of its vertices with their joints and
// weights unchanged, fewer triangles level by level, and an error that grows.
#include <gtest/gtest.h>

#include <cmath>

#include "asset/mesh_lod.h"
#include "render_support.h"

using namespace crowdprof;

TEST(MeshLod, TheHumanoidGetsThreeCoarserLevelsOfItsOwnVertices) {
  const SkinnedMesh& full = test::default_humanoid().mesh;
  const std::vector<MeshLod> levels = build_mesh_lods(full);
  ASSERT_EQ(levels.size(), 3u);
  size_t triangles = full.triangle_count(), vertices = full.vertex_count();
  float error = 0;
  for (size_t l = 0; l < levels.size(); ++l) {
    const MeshLod& level = levels[l];
    const SkinnedMesh& m = level.mesh;
    SCOPED_TRACE("level " + std::to_string(l + 1));
    EXPECT_LT(m.triangle_count(), triangles);
    EXPECT_LT(m.vertex_count(), vertices);
    // The share asked for, within what the error limit let the simplifier reach.
    EXPECT_LE(m.triangle_count(),
              static_cast<size_t>(static_cast<double>(full.triangle_count()) * level.target_share * 1.1) + 1);
    EXPECT_TRUE(std::isfinite(level.error));
    EXPECT_GE(level.error, error);
    triangles = m.triangle_count();
    vertices = m.vertex_count();
    error = level.error;
    ASSERT_EQ(level.source_vertex.size(), m.vertex_count());
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      const uint32_t from = level.source_vertex[v];
      ASSERT_LT(from, full.vertex_count());
      EXPECT_EQ(m.positions[v], full.positions[from]);
      EXPECT_EQ(m.normals[v], full.normals[from]);
      EXPECT_EQ(m.joints[v], full.joints[from]);
      EXPECT_EQ(m.weights[v], full.weights[from]);
    }
    // Every vertex is used, and every index is one of the level's.
    std::vector<uint8_t> used(m.vertex_count(), 0);
    for (uint32_t i : m.indices) {
      ASSERT_LT(i, m.vertex_count());
      used[i] = 1;
    }
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
    ASSERT_EQ(m.primitives.size(), 1u);
    EXPECT_EQ(m.primitives[0].index_count, m.indices.size());
  }
  // A tenth of the triangles stays within 5% of the character's extent.
  EXPECT_LT(levels.back().error, 0.05f * 2.0f);
}

TEST(MeshLod, TheLevelsAreTheSameEveryTime) {
  const SkinnedMesh& full = test::default_humanoid().mesh;
  const std::vector<MeshLod> a = build_mesh_lods(full), b = build_mesh_lods(full);
  ASSERT_EQ(a.size(), b.size());
  for (size_t l = 0; l < a.size(); ++l) {
    EXPECT_EQ(a[l].mesh.indices, b[l].mesh.indices);
    EXPECT_EQ(a[l].source_vertex, b[l].source_vertex);
  }
}

TEST(MeshLod, AMeshTooSmallOrMalformedHasNoLevels) {
  SkinnedMesh one;
  one.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  one.joints.assign(3, glm::u16vec4(0));
  one.weights.assign(3, glm::vec4(1, 0, 0, 0));
  one.indices = {0, 1, 2};
  one.primitives = {{0, 3, 0, 3}};
  EXPECT_TRUE(build_mesh_lods(one).empty());
  EXPECT_TRUE(build_mesh_lods(SkinnedMesh{}).empty());
  // Not a mesh the simplifier takes (it would abort): no levels, no crash.
  SkinnedMesh partial = test::default_humanoid().mesh;
  partial.indices.pop_back();
  EXPECT_TRUE(build_mesh_lods(partial).empty());
  SkinnedMesh past = test::default_humanoid().mesh;
  past.indices[7] = static_cast<uint32_t>(past.vertex_count());
  EXPECT_TRUE(build_mesh_lods(past).empty());
}

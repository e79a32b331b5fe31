#include "asset/mesh_lod.h"

#include <algorithm>

#include <meshoptimizer.h>

namespace crowdprof {

namespace {

// Level `indices` (into the full mesh) with its own vertices: those the
// triangles use, in the order they first use them.
MeshLod compact(const SkinnedMesh& full, std::vector<uint32_t> indices) {
  const size_t full_vertices = full.vertex_count();
  meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), full_vertices);
  std::vector<uint32_t> remap(full_vertices);
  const size_t kept = meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), full_vertices);
  MeshLod level;
  SkinnedMesh& m = level.mesh;
  m.positions.resize(kept);
  m.normals.resize(kept);
  m.joints.resize(kept);
  m.weights.resize(kept);
  level.source_vertex.resize(kept);
  for (size_t v = 0; v < full_vertices; ++v) {
    const uint32_t to = remap[v];
    if (to == ~0u) continue;  // no triangle of the level uses it
    m.positions[to] = full.positions[v];
    m.normals[to] = full.normals[v];
    m.joints[to] = full.joints[v];
    m.weights[to] = full.weights[v];
    level.source_vertex[to] = static_cast<uint32_t>(v);
  }
  m.indices.resize(indices.size());
  for (size_t i = 0; i < indices.size(); ++i) m.indices[i] = remap[indices[i]];
  m.primitives.push_back({0, static_cast<uint32_t>(m.indices.size()), 0, static_cast<uint32_t>(kept)});
  return level;
}

}  // namespace

float bind_pose_height(const SkinnedMesh& mesh) {
  float low = 0, high = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    low = v ? std::min(low, mesh.positions[v].y) : mesh.positions[v].y;
    high = v ? std::max(high, mesh.positions[v].y) : mesh.positions[v].y;
  }
  return high - low;
}

std::vector<MeshLod> build_mesh_lods(const SkinnedMesh& mesh, std::span<const MeshLodTarget> targets) {
  std::vector<MeshLod> levels;
  // meshoptimizer asserts (aborts) on a partial triangle or an index past the
  // vertices: the loader refuses both, but a mesh made elsewhere may not.
  if (mesh.indices.size() < 3 || mesh.indices.size() % 3 != 0 || mesh.vertex_count() == 0) return levels;
  for (uint32_t i : mesh.indices)
    if (i >= mesh.vertex_count()) return levels;
  const float* positions = &mesh.positions[0].x;
  const float scale = meshopt_simplifyScale(positions, mesh.vertex_count(), sizeof(glm::vec3));
  size_t previous = mesh.indices.size();
  std::vector<uint32_t> simplified(mesh.indices.size());
  for (const MeshLodTarget& target : targets) {
    const size_t wanted = static_cast<size_t>(static_cast<double>(mesh.triangle_count()) * target.share) * 3;
    float error = 0;
    const size_t count = meshopt_simplify(simplified.data(), mesh.indices.data(), mesh.indices.size(), positions,
                                          mesh.vertex_count(), sizeof(glm::vec3), wanted, target.max_error, 0, &error);
    if (count == 0 || count >= previous) continue;
    MeshLod level = compact(mesh, std::vector<uint32_t>(simplified.begin(), simplified.begin() + count));
    level.target_share = target.share;
    level.error = error * scale;
    previous = count;
    levels.push_back(std::move(level));
  }
  return levels;
}

}  // namespace crowdprof

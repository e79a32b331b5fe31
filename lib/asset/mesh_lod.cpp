#include "asset/mesh_lod.h"

#include <algorithm>

#include <meshoptimizer.h>

#include "asset/standing.h"
#include "asset/vertex_order.h"

namespace crowdprof {

namespace {

// Level `indices` (into the full mesh) with its own vertices: those the
// triangles use, ordered by their joints (asset/vertex_order.h).
MeshLod compact(const SkinnedMesh& full, std::vector<uint32_t> indices) {
  const size_t full_vertices = full.vertex_count();
  meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), full_vertices);
  std::vector<uint32_t> remap(full_vertices);
  const size_t kept = meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), full_vertices);
  MeshLod level;
  level.cache_ordered = true;
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
  // Then for skinning (asset/vertex_order.h), as a bench orders the full mesh's.
  const std::vector<uint32_t> old_of_new = order_vertices_by_joints(m);
  std::vector<uint32_t> source(kept);
  for (size_t v = 0; v < kept; ++v) source[v] = level.source_vertex[old_of_new[v]];
  level.source_vertex = std::move(source);
  return level;
}

}  // namespace

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

namespace {

// The closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
glm::vec3 closest_on_triangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const float denom = va + vb + vc;
  if (!(denom > 0)) return a;  // a degenerate triangle: its first corner
  return a + ab * (vb / denom) + ac * (vc / denom);
}

// The largest distance from a vertex of `from` to the triangles of `to`.
float one_sided_distance(const SkinnedMesh& from, const SkinnedMesh& to) {
  const size_t triangles = to.indices.size() / 3;
  if (from.positions.empty() || triangles == 0) return 0.0f;
  constexpr size_t kPairs = 50'000'000;
  const size_t stride = std::max<size_t>(1, (from.positions.size() * triangles + kPairs - 1) / kPairs);
  float worst = 0;
  for (size_t v = 0; v < from.positions.size(); v += stride) {
    const glm::vec3& p = from.positions[v];
    float best = std::numeric_limits<float>::max();
    for (size_t t = 0; t < triangles && best > worst; ++t) {
      const glm::vec3 q = closest_on_triangle(p, to.positions[to.indices[3 * t]], to.positions[to.indices[3 * t + 1]],
                                              to.positions[to.indices[3 * t + 2]]);
      const glm::vec3 d = p - q;
      best = std::min(best, glm::dot(d, d));
    }
    worst = std::max(worst, best);  // no closer triangle than the worst so far: it cannot raise it
  }
  return std::sqrt(worst);
}

}  // namespace

float surface_distance(const SkinnedMesh& a, const SkinnedMesh& b) {
  return std::max(one_sided_distance(a, b), one_sided_distance(b, a));
}

std::vector<MeshLod> mesh_lods_of(const Character& character) {
  const float world_per_mesh_unit = standing_of(character).world_per_mesh_unit;
  if (character.file_lods.empty()) {
    // meshoptimizer breaks ties by vertex index: simplified from one order,
    // the levels are the same for a bench's ordered character and `info`'s.
    SkinnedMesh ordered = character.mesh;
    order_vertices_by_joints(ordered);
    std::vector<MeshLod> lods = build_mesh_lods(ordered);
    for (MeshLod& lod : lods) lod.error *= world_per_mesh_unit;
    return lods;
  }
  std::vector<MeshLod> lods;
  const double full = static_cast<double>(std::max<size_t>(1, character.mesh.triangle_count()));
  for (size_t l = 0; l < character.file_lods.size() && l + 1 < kMeshLevels; ++l) {
    MeshLod lod;
    lod.mesh = character.file_lods[l];
    lod.target_share = static_cast<float>(static_cast<double>(lod.mesh.triangle_count()) / full);
    lod.error =
        world_per_mesh_unit * (l < character.file_lod_errors.size() ? character.file_lod_errors[l]
                                                                    : surface_distance(character.mesh, lod.mesh));
    lods.push_back(std::move(lod));
  }
  return lods;
}

const char* mesh_lods_source(const Character& character) {
  return character.file_lods.empty() ? "meshoptimizer" : "MSFT_lod";
}

}  // namespace crowdprof

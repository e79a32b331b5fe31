#include "asset/vertex_order.h"

#include <algorithm>
#include <array>
#include <numeric>

#include <meshoptimizer.h>

namespace crowdprof {

namespace {

// A vertex's joints of non-zero weight, ascending, then 65536s (past any
// joint, so a vertex of fewer joints sorts after one that adds to them:
// {1, 3, 5} before {1, 3}).
using JointSet = std::array<uint32_t, 4>;

JointSet joint_set(const SkinnedMesh& mesh, size_t v) {
  JointSet set{65536, 65536, 65536, 65536};
  int used = 0;
  for (int k = 0; k < 4; ++k)
    if (mesh.weights[v][k] != 0.0f) set[static_cast<size_t>(used++)] = mesh.joints[v][k];
  std::sort(set.begin(), set.begin() + used);
  return set;
}

// The primitives' vertex ranges cover [0, n) once each.
bool ranges_partition(const SkinnedMesh& mesh) {
  const size_t n = mesh.vertex_count();
  std::vector<char> covered(n, 0);
  size_t count = 0;
  for (const Primitive& p : mesh.primitives) {
    if (p.first_vertex > n || p.vertex_count > n - p.first_vertex) return false;
    for (size_t v = p.first_vertex; v < p.first_vertex + p.vertex_count; ++v) {
      if (covered[v]) return false;
      covered[v] = 1;
      ++count;
    }
  }
  return count == n;
}

template <typename T>
void permute(std::vector<T>& values, const std::vector<uint32_t>& old_of_new) {
  std::vector<T> out(values.size());
  for (size_t v = 0; v < out.size(); ++v) out[v] = values[old_of_new[v]];
  values = std::move(out);
}

}  // namespace

std::vector<uint32_t> order_vertices_by_joints(SkinnedMesh& mesh) {
  const size_t n = mesh.vertex_count();
  std::vector<uint32_t> old_of_new(n);
  std::iota(old_of_new.begin(), old_of_new.end(), 0u);
  if (mesh.normals.size() != n || mesh.joints.size() != n || mesh.weights.size() != n || !ranges_partition(mesh))
    return old_of_new;

  std::vector<JointSet> sets(n);
  for (size_t v = 0; v < n; ++v) sets[v] = joint_set(mesh, v);
  for (const Primitive& p : mesh.primitives) {
    auto first = old_of_new.begin() + p.first_vertex;
    std::stable_sort(first, first + p.vertex_count, [&](uint32_t a, uint32_t b) { return sets[a] < sets[b]; });
  }
  permute(mesh.positions, old_of_new);
  permute(mesh.normals, old_of_new);
  permute(mesh.joints, old_of_new);
  permute(mesh.weights, old_of_new);
  std::vector<uint32_t> new_of_old(n);
  for (size_t v = 0; v < n; ++v) new_of_old[old_of_new[v]] = static_cast<uint32_t>(v);
  for (uint32_t& index : mesh.indices)
    if (index < n) index = new_of_old[index];
  return old_of_new;
}

std::vector<uint32_t> vertex_cache_order(const SkinnedMesh& mesh) {
  std::vector<uint32_t> out = mesh.indices;
  const size_t n = mesh.vertex_count();
  for (const Primitive& p : mesh.primitives) {
    if (p.first_index > out.size() || p.index_count > out.size() - p.first_index || p.index_count % 3 != 0) continue;
    uint32_t* first = out.data() + p.first_index;
    // meshoptimizer asserts (aborts) on an index past the vertex count.
    if (std::any_of(first, first + p.index_count, [&](uint32_t i) { return i >= n; })) continue;
    meshopt_optimizeVertexCache(first, first, p.index_count, n);
  }
  return out;
}

VertexCacheFigures analyze_vertex_cache(std::span<const uint32_t> indices, size_t vertex_count,
                                        const VertexCacheModel& model) {
  VertexCacheFigures figures;
  if (indices.size() < 3 || indices.size() % 3 != 0 ||
      std::any_of(indices.begin(), indices.end(), [&](uint32_t i) { return i >= vertex_count; }))
    return figures;
  const meshopt_VertexCacheStatistics stats = meshopt_analyzeVertexCache(
      indices.data(), indices.size(), vertex_count, model.cache_size, model.warp_size, model.primgroup_size);
  // Over the vertices the triangles use, not the array's: a primitive uses a
  // part of a mesh's vertices.
  std::vector<char> used(vertex_count, 0);
  size_t distinct = 0;
  for (uint32_t i : indices) distinct += used[i] ? 0 : (used[i] = 1);
  figures.acmr = static_cast<double>(stats.vertices_transformed) / static_cast<double>(indices.size() / 3);
  figures.atvr = static_cast<double>(stats.vertices_transformed) / static_cast<double>(distinct);
  return figures;
}

void order_vertices_for_skinning(Character& character) {
  order_vertices_by_joints(character.mesh);
  for (SkinnedMesh& level : character.file_lods) order_vertices_by_joints(level);
}

}  // namespace crowdprof

// The order of a skinned mesh's vertices, chosen for the skinning loop.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "asset/character.h"

namespace crowdprof {

// Reorders the vertices of each of `mesh`'s primitives by the set of joints
// they weigh (its joint indices ascending, compared as words), keeping the
// file's order among vertices of one set, and renumbers `mesh.indices` to
// match: the same triangles, drawn alike. Returns, per new vertex, the index it
// had before. Why: skinning blends, per batch of 16 consecutive vertices, every
// joint any of them uses (skinning/skinning_plan.h); in the file's order the
// batches of Khronos' CesiumMan blend 5.06 joints, in this order 2.62 (the
// Fox 5.31 and 1.95, the bundled humanoid 3.06 and 2.64). Vertices of a
// primitive stay in its range; a mesh whose primitives' vertex ranges overlap,
// leave vertices out or fall outside the arrays is left as it is (identity).
std::vector<uint32_t> order_vertices_by_joints(SkinnedMesh& mesh);

// `mesh.indices` with each primitive's triangles in meshoptimizer's vertex-
// cache order (meshopt_optimizeVertexCache), for the GPU's post-transform
// cache: the same triangles, each wound as before, over the same vertices in
// the same order, so skinning's batches are untouched. Only the GPU's index
// buffer takes it: mesh LOD simplifies the file's order, and `info` analyses
// both. A primitive whose indices fall outside the vertices is left as it is.
std::vector<uint32_t> vertex_cache_order(const SkinnedMesh& mesh);

// A GPU's post-transform cache as meshoptimizer's analyser models it: a FIFO
// of cache_size vertices, warps of warp_size vertices, primitive groups of
// primgroup_size triangles (0: no such limit).
struct VertexCacheModel {
  std::string_view name;
  unsigned cache_size, warp_size, primgroup_size;
};
inline constexpr VertexCacheModel kVertexCacheModels[] = {
    {"NVIDIA-like", 32, 32, 32}, {"AMD-like", 14, 64, 128}, {"Intel-like", 128, 0, 0}};

// What the model shades for `indices` (triangles over vertices below
// vertex_count): ACMR, vertices shaded per triangle (0.5 at best on a big
// regular mesh, 3 at worst), and ATVR, per vertex the triangles use (1 at
// best: each shaded once). Allocates.
struct VertexCacheFigures {
  double acmr = 0, atvr = 0;
};
VertexCacheFigures analyze_vertex_cache(std::span<const uint32_t> indices, size_t vertex_count,
                                        const VertexCacheModel& model);

// Orders the vertices of `character`'s mesh and of the file's own levels
// (MSFT_lod) as above. The loader keeps the file's order (what `info` and its
// messages describe); a bench orders its characters once, after loading them.
void order_vertices_for_skinning(Character& character);

}  // namespace crowdprof

// Mesh LOD (issue 29): coarser versions of a skinned mesh for copies small on
// screen, made with meshoptimizer's simplifier. Each level keeps only the
// vertices its triangles use, so a far copy *skins* fewer vertices, not only
// draws fewer triangles; their joints and weights are the full mesh's.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "asset/character.h"

namespace crowdprof {

// One simplified level of a mesh.
struct MeshLod {
  SkinnedMesh mesh;                     // its own vertices and triangles (indices into them), one primitive
  std::vector<uint32_t> source_vertex;  // per vertex of `mesh`: the full mesh's vertex it is
  float target_share = 1;               // of the full mesh's triangles asked for
  // How far the simplified surface strays from the full one: from
  // build_mesh_lods, meshoptimizer's estimate in the mesh's own (bind-pose)
  // units; from mesh_lods_of, in world units (asset/standing.h), as every
  // figure shows it.
  float error = 0;
  // Its triangles in vertex-cache order (build_mesh_lods makes them so; a
  // file's own levels come as the file lists them).
  bool cache_ordered = false;
};

// The levels built by default: half, a quarter and a tenth of the triangles,
// each allowed to stray at most 1%, 2% and 5% of the mesh's extent (past
// that, the simplifier stops short of the share and the level has more).
struct MeshLodTarget {
  float share = 1, max_error = 0;  // max_error: relative to the mesh's extent
};
inline constexpr MeshLodTarget kMeshLodTargets[] = {{0.5f, 0.01f}, {0.25f, 0.02f}, {0.1f, 0.05f}};
// Levels a copy can draw: the full mesh and at most three coarser ones.
inline constexpr size_t kMeshLevels = 4;

// Simplifies `mesh` (bind pose) to each target in turn, each level from the
// full mesh. A level that would not have fewer triangles than the one before
// it is left out, so a small mesh may get fewer levels (or none). The vertices
// of each level are ordered by their joints (asset/vertex_order.h), ties in
// the order its triangles first use them (meshoptimizer's vertex fetch order);
// its triangles are in vertex-cache order. Allocates.
std::vector<MeshLod> build_mesh_lods(const SkinnedMesh& mesh, std::span<const MeshLodTarget> targets = kMeshLodTargets);

// How far two surfaces stray from each other (bind pose, the meshes' units):
// the largest distance from a vertex of either to the other's triangles (a
// symmetric, vertex-sampled Hausdorff distance). Past 50 million vertex-
// triangle pairs a side, every Nth vertex of that side is taken. Allocates nothing.
float surface_distance(const SkinnedMesh& a, const SkinnedMesh& b);

// The levels mesh LOD draws for `character`: the file's own (MSFT_lod,
// Character::file_lods, which the loader keeps to the first three that are
// each coarser than the one before; its surface distance from the full mesh,
// measured at load, as each one's error and its share of the triangles as
// its target), else build_mesh_lods of its mesh ordered by joints
// (asset/vertex_order.h; source_vertex then numbers that order's vertices), so
// a character gives the same levels ordered or not. Errors in world units: the
// mesh's times Standing::world_per_mesh_unit. Allocates.
std::vector<MeshLod> mesh_lods_of(const Character& character);
// "MSFT_lod" when mesh_lods_of takes the file's levels, else "meshoptimizer".
const char* mesh_lods_source(const Character& character);

}  // namespace crowdprof

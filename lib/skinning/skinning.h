// Software skinning: the thesis's equations 1 and 2 over a range of a mesh
// prepared once by build_skinning_plan.
#pragma once

#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "animation/skin_matrix.h"
#include "skinning/packed_vertex.h"
#include "skinning/skinning_plan.h"

namespace crowdprof {

// Linear blend skinning of vertices [first_vertex, first_vertex + vertex_count)
// of the mesh `plan` was built from. Each vertex's matrix is the weighted sum of
// its joints' skinning matrices; positions go through the whole matrix
// (equation 1), normals through its 3x3 part (equation 2).
//
// Normals are renormalised wherever blending can change their length: every
// vertex with more than one influence. A batch of vertices that each have one
// influence (weight 1, unit normal) keeps the rotated normal as it is when every
// such joint's skinning matrix is a rotation (its 3x3 columns orthonormal within
// kRigidTolerance, checked on each run); else it is renormalised too. A normal
// that blends to zero length comes out zero.
//
// The kernels run 16 vertices at a time on the widest SIMD target the CPU has
// (simd_target.h), in the same order on every target. Any split of a mesh into
// ranges on any threads gives the same bits; so does every target of one
// arithmetic: fused multiply-adds on AVX2 and up, separate multiplies and adds
// on SSE4 and below (skinning_fuses_multiply_add). The two agree within 1e-5
// of the character's height (tested), not bit for bit. A vertex's batch blends every
// joint the batch uses, with weight 0 for those the vertex does not: a NaN or
// infinite matrix spreads to the batch's other vertices.
struct SkinningJob {
  std::span<const SkinMatrix> skinning_matrices;  // one per joint (pose.h)
  const SkinningPlan* plan = nullptr;
  size_t first_vertex = 0;
  size_t vertex_count = 0;
  // out_positions[i] and out_normals[i] receive vertex first_vertex + i; both
  // spans hold exactly vertex_count elements.
  std::span<glm::vec3> out_positions;
  std::span<glm::vec3> out_normals;
  // Non-temporal (streaming) stores: for output headed to memory rather than
  // to a cache that will still hold it when it is read (output_stores.h). Only
  // the batches whose outputs start on a 64-byte boundary stream; the others,
  // and the bits written, are as without. Fenced before Run returns.
  bool streaming_stores = false;

  // Plan set, palette covering its joints, range inside the mesh, outputs sized
  // to the range. Constant time: the joint indices were checked with the plan.
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// SkinningJob with its output in the packed format (packed_vertex.h): the same
// arithmetic, then each vertex's float position and normal encoded, exactly
// as quantise_position and pack_normal would, on every SIMD target.
struct PackedSkinningJob {
  std::span<const SkinMatrix> skinning_matrices;
  const SkinningPlan* plan = nullptr;
  // The box positions are quantised in; those outside it are clamped to it.
  const PositionQuantisation* quantisation = nullptr;
  size_t first_vertex = 0;
  size_t vertex_count = 0;
  // Vertex first_vertex + i's codes at out_positions[3 i, 3 i + 3) and its
  // normal's word at out_normals[i]: 3 x vertex_count and vertex_count long.
  std::span<uint16_t> out_positions;
  std::span<uint32_t> out_normals;

  // As SkinningJob's, with the quantisation set.
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

// How far a single-influence joint's 3x3 columns may be from orthonormal (each
// entry of M^T M against the identity) for its normals to keep their length:
// the skinned normal is then within 1.5e-5 of unit length.
constexpr float kRigidTolerance = 1e-5f;

// True when the 3x3 part of `m` is a rotation within kRigidTolerance.
bool is_rigid(const SkinMatrix& m);

}  // namespace crowdprof

// A skinned mesh prepared once, at load, for the skinning loop: vertices in
// batches of 16 in structure-of-arrays form, each batch with the joints its
// vertices use, so that the per-frame job only multiplies and adds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "asset/character.h"
#include "skinning/output_buffer.h"

namespace crowdprof {

// Vertices per batch. One batch is one AVX-512 vector per coordinate, two AVX2
// vectors, four SSE vectors: the plan is the same for every SIMD target, so
// every target does the same steps on every vertex, in the same order.
constexpr size_t kSkinBatch = 16;

// One batch of kSkinBatch consecutive vertices (the last one padded).
struct SkinBatch {
  uint32_t data = 0;         // first float of the batch in SkinningPlan::data
  uint32_t first_joint = 0;  // its joints: SkinningPlan::joints[first_joint, + joint_count)
  uint16_t joint_count = 0;
  // Every vertex of the batch has one influence (weight exactly 1) and a unit
  // normal: when that joint's skinning matrix is a rotation (no scale), the
  // skinned normal is unit length already and the job skips renormalising it.
  uint16_t single_influence = 0;
};

// Built by build_skinning_plan; read-only afterwards, shared by every copy.
struct SkinningPlan {
  size_t vertex_count = 0;
  size_t joint_count = 0;  // every joint index of the mesh is below this
  std::vector<SkinBatch> batches;
  // Per batch, the union of the joints its vertices weigh non-zero, ascending.
  std::vector<uint16_t> joints;
  // Per batch, 64-byte aligned, kSkinBatch floats per row: position x, y, z,
  // normal x, y, z, then one row of weights per joint of the batch (a vertex's
  // weight for a joint it does not use is 0). Padding lanes are all 0.
  std::vector<float, CacheLineAllocator<float>> data;
  // The joints of the single-influence batches, ascending, without repeats: the
  // job checks these skinning matrices for scale before skipping renormalisation.
  std::vector<uint16_t> single_joints;
  // Every joint some batch uses, ascending, without repeats: the kernels that
  // broadcast the palette into a table first (SSE4 and SSSE3) fill these only.
  std::vector<uint16_t> skin_joints;

  size_t batch_count() const { return batches.size(); }
};

// Fills `plan` from `mesh`, whose joint indices must all be below `joint_count`
// (those of zero weights too) and whose arrays must be sized alike. Returns ""
// or, leaving `plan` empty, what is wrong with the mesh. Vertex order is kept:
// batch b holds vertices [16 b, 16 b + 16).
std::string build_skinning_plan(const SkinnedMesh& mesh, size_t joint_count, SkinningPlan* plan);

}  // namespace crowdprof

#include "skinning/skinning.h"

#include <cmath>

#include "skinning/skinning_kernels.h"

namespace crowdprof {

bool is_rigid(const SkinMatrix& m) {
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      const float dot = glm::dot(glm::vec3(m[i]), glm::vec3(m[j]));
      if (!(std::abs(dot - (i == j ? 1.0f : 0.0f)) <= kRigidTolerance)) return false;
    }
  return true;
}

namespace {

bool valid_range(const SkinningPlan* plan, size_t first_vertex, size_t vertex_count) {
  if (plan == nullptr) return false;
  const size_t n = plan->vertex_count;
  return first_vertex <= n && vertex_count <= n - first_vertex;
}

// The kernel's arguments common to both formats. A handful of joints (those of
// the single-influence batches) are checked for scale, cheaper than the
// renormalisation it saves on their vertices.
SkinKernelArgs kernel_args(std::span<const SkinMatrix> skinning_matrices, const SkinningPlan* plan, size_t first_vertex,
                           size_t vertex_count) {
  bool keep = true;
  for (uint16_t joint : plan->single_joints)
    if (!is_rigid(skinning_matrices[joint])) {
      keep = false;
      break;
    }
  SkinKernelArgs args;
  args.plan = plan;
  args.palette = &skinning_matrices[0][0][0];
  args.first_vertex = first_vertex;
  args.end_vertex = first_vertex + vertex_count;
  args.keep_single_normals = keep;
  return args;
}

}  // namespace

bool SkinningJob::Validate() const {
  if (!valid_range(plan, first_vertex, vertex_count)) return false;
  if (out_positions.size() != vertex_count || out_normals.size() != vertex_count) return false;
  return vertex_count == 0 || skinning_matrices.size() >= plan->joint_count;
}

bool SkinningJob::Run() const {
  if (!Validate()) return false;
  if (vertex_count == 0) return true;
  SkinKernelArgs args = kernel_args(skinning_matrices, plan, first_vertex, vertex_count);
  args.positions = &out_positions[0].x;
  args.normals = &out_normals[0].x;
  args.stream = streaming_stores;
  run_skinning_kernel(args);
  return true;
}

bool PackedSkinningJob::Validate() const {
  if (!valid_range(plan, first_vertex, vertex_count) || quantisation == nullptr) return false;
  if (out_positions.size() != 3 * vertex_count || out_normals.size() != vertex_count) return false;
  return vertex_count == 0 || skinning_matrices.size() >= plan->joint_count;
}

bool PackedSkinningJob::Run() const {
  if (!Validate()) return false;
  if (vertex_count == 0) return true;
  SkinKernelArgs args = kernel_args(skinning_matrices, plan, first_vertex, vertex_count);
  args.packed_positions = out_positions.data();
  args.packed_normals = out_normals.data();
  for (int a = 0; a < 3; ++a) {
    args.quantisation_min[a] = quantisation->min[a];
    args.quantisation_scale[a] = quantisation->scale[a];
  }
  run_skinning_kernel(args);
  return true;
}

}  // namespace crowdprof

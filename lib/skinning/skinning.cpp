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

bool SkinningJob::Validate() const {
  if (plan == nullptr) return false;
  const size_t n = plan->vertex_count;
  if (first_vertex > n || vertex_count > n - first_vertex) return false;
  if (out_positions.size() != vertex_count || out_normals.size() != vertex_count) return false;
  return vertex_count == 0 || skinning_matrices.size() >= plan->joint_count;
}

bool SkinningJob::Run() const {
  if (!Validate()) return false;
  if (vertex_count == 0) return true;
  // A handful of joints (those of the single-influence batches), so cheaper
  // than the renormalisation it saves on their vertices.
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
  args.positions = &out_positions[0].x;
  args.normals = &out_normals[0].x;
  args.keep_single_normals = keep;
  run_skinning_kernel(args);
  return true;
}

}  // namespace crowdprof

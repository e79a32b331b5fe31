#include "skinning/skinning_plan.h"

#include <algorithm>
#include <cmath>

namespace crowdprof {

std::string build_skinning_plan(const SkinnedMesh& mesh, size_t joint_count, SkinningPlan* plan) {
  *plan = SkinningPlan{};
  const size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || mesh.joints.size() != n || mesh.weights.size() != n)
    return "the mesh's positions, normals, joints and weights differ in count";
  if (joint_count > 65536) return "more than 65,536 joints";
  // Every index is checked here, once, so the per-frame job reads the palette
  // without looking (those of zero weight too: the file said them).
  for (size_t v = 0; v < n; ++v)
    for (int k = 0; k < 4; ++k)
      if (mesh.joints[v][k] >= joint_count)
        return "vertex " + std::to_string(v) + " uses joint " + std::to_string(mesh.joints[v][k]) + " of " +
               std::to_string(joint_count);

  SkinningPlan out;
  out.vertex_count = n;
  out.joint_count = joint_count;
  const size_t batches = (n + kSkinBatch - 1) / kSkinBatch;
  out.batches.resize(batches);
  std::vector<uint16_t> used;
  for (size_t b = 0; b < batches; ++b) {
    const size_t first = b * kSkinBatch, count = std::min(kSkinBatch, n - first);
    used.clear();
    bool single = true;
    for (size_t v = first; v < first + count; ++v) {
      int influences = 0;
      for (int k = 0; k < 4; ++k) {
        if (mesh.weights[v][k] == 0.0f) continue;
        ++influences;
        used.push_back(mesh.joints[v][k]);
      }
      // Renormalising a single-influence normal changes nothing when the weight
      // is exactly 1, the normal unit length and the joint's matrix a rotation.
      const glm::vec3 normal = mesh.normals[v];
      const float length2 = glm::dot(normal, normal);
      if (influences != 1 || glm::dot(mesh.weights[v], glm::vec4(1.0f)) != 1.0f || std::abs(length2 - 1.0f) > 1e-6f)
        single = false;
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());

    SkinBatch& batch = out.batches[b];
    batch.data = static_cast<uint32_t>(out.data.size());
    batch.first_joint = static_cast<uint32_t>(out.joints.size());
    batch.joint_count = static_cast<uint16_t>(used.size());
    batch.single_influence = single ? 1 : 0;
    out.joints.insert(out.joints.end(), used.begin(), used.end());
    if (single) out.single_joints.insert(out.single_joints.end(), used.begin(), used.end());

    out.data.resize(out.data.size() + (6 + used.size()) * kSkinBatch, 0.0f);
    float* rows = out.data.data() + batch.data;
    for (size_t lane = 0; lane < count; ++lane) {
      const size_t v = first + lane;
      for (int c = 0; c < 3; ++c) {
        rows[c * kSkinBatch + lane] = mesh.positions[v][c];
        rows[(3 + c) * kSkinBatch + lane] = mesh.normals[v][c];
      }
      // A joint named twice by one vertex gets the sum of its weights.
      for (int k = 0; k < 4; ++k) {
        if (mesh.weights[v][k] == 0.0f) continue;
        const size_t row =
            static_cast<size_t>(std::lower_bound(used.begin(), used.end(), mesh.joints[v][k]) - used.begin());
        rows[(6 + row) * kSkinBatch + lane] += mesh.weights[v][k];
      }
    }
  }
  auto sort_unique = [](std::vector<uint16_t>& list) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  };
  sort_unique(out.single_joints);
  out.skin_joints = out.joints;
  sort_unique(out.skin_joints);
  if (out.data.size() > UINT32_MAX) return "too many vertices for one skinning plan";
  *plan = std::move(out);
  return {};
}

}  // namespace crowdprof

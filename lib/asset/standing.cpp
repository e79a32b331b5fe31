#include "asset/standing.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

namespace crowdprof {

Standing standing_of(const Character& character) {
  const Skeleton& s = character.skeleton;
  const SkinnedMesh& mesh = character.mesh;
  const size_t joints = s.joint_count();
  // model[j] = model[parent] * parent_offsets[j] * TRS(j), as LocalToModelJob.
  std::vector<glm::mat4> skin(joints);
  std::vector<glm::mat4> model(joints);
  for (size_t j = 0; j < joints; ++j) {
    const glm::mat4 local = glm::translate(glm::mat4(1.0f), s.rest_translations[j]) *
                            glm::mat4_cast(s.rest_rotations[j]) * glm::scale(glm::mat4(1.0f), s.rest_scales[j]);
    const int parent = s.parents[j];
    model[j] = (parent >= 0 ? model[static_cast<size_t>(parent)] : glm::mat4(1.0f)) * s.parent_offsets[j] * local;
    skin[j] = model[j] * s.inverse_binds[j];
  }
  Standing standing;
  if (mesh.positions.empty() || joints == 0) return standing;
  float low = 0, high = 0;
  double scale_sum = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    glm::mat4 m(0.0f);
    for (int i = 0; i < 4; ++i)
      if (mesh.weights[v][i] > 0) m += skin[std::min<size_t>(mesh.joints[v][i], joints - 1)] * mesh.weights[v][i];
    const float y = (m * glm::vec4(mesh.positions[v], 1.0f)).y;
    low = v ? std::min(low, y) : y;
    high = v ? std::max(high, y) : y;
    scale_sum += std::cbrt(std::abs(static_cast<double>(glm::determinant(glm::mat3(m)))));
  }
  standing.height = high - low;
  standing.world_per_mesh_unit = static_cast<float>(scale_sum / static_cast<double>(mesh.positions.size()));
  return standing;
}

}  // namespace crowdprof

#include "asset/mesh_normals.h"

namespace crowdprof {

std::vector<glm::vec3> face_normals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
  std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
  for (size_t i = 0; i + 2 < indices.size(); i += 3) {
    uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
    if (a >= positions.size() || b >= positions.size() || c >= positions.size()) continue;
    // The cross product's length is twice the area: larger faces weigh more.
    glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
    normals[a] += n;
    normals[b] += n;
    normals[c] += n;
  }
  for (glm::vec3& n : normals) {
    float length = glm::length(n);
    n = length > 1e-20f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return normals;
}

}  // namespace crowdprof

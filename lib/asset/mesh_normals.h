// Vertex normals for meshes that come without them.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace crowdprof {

// Area-weighted average of the normals of the triangles around each vertex
// (indices relative to `positions`). A vertex on no triangle, or only on
// degenerate ones, gets +Z so that every normal has unit length.
std::vector<glm::vec3> face_normals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);

}  // namespace crowdprof

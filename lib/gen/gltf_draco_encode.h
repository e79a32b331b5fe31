// Draco compression of one skinned primitive, for the glTF writer's
// KHR_draco_mesh_compression output. Internal to gltf_writer.cpp.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace crowdprof {

struct DracoPrimitive {
  std::vector<uint8_t> bytes;  // the compressed stream
  // Draco attribute unique ids, for the extension's "attributes" object.
  int position_id = -1, normal_id = -1, joints_id = -1, weights_id = -1;
  // What a decoder gets back, which the glTF accessors must describe.
  size_t points = 0, faces = 0;
  glm::vec3 min{0.0f}, max{0.0f};  // of the decoded positions
};

// Encodes a triangle list (indices relative to the vertex spans) with joints
// stored as uint8 when `joints_u8`, else uint16, to match the accessor type.
// Throws std::runtime_error if Draco refuses the mesh.
DracoPrimitive encode_draco_primitive(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                      std::span<const glm::u16vec4> joints, std::span<const glm::vec4> weights,
                                      std::span<const uint32_t> indices, bool joints_u8);

}  // namespace crowdprof

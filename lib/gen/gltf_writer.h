// Writing a Character as glTF 2.0, so that generated characters (and any
// character crowdprof holds) can be saved and loaded back like any other asset.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "asset/character.h"

namespace crowdprof {

struct GltfWriteOptions {
  // true: one .glb. false: one .gltf (JSON) whose single buffer is embedded as
  // a base64 data: URI, so that either way one path holds the whole asset.
  bool binary = true;
  // Each primitive's POSITION, NORMAL, JOINTS_0 and WEIGHTS_0 and indices as one
  // KHR_draco_mesh_compression stream (edgebreaker; position 14 bits, normal 10,
  // weights 12; joints are integers and come back exact). The extension is then
  // required. Draco may reorder a primitive's vertices: the decoded primitive
  // holds the same vertices and triangles, not in the same order.
  bool draco = false;
};

// The file's bytes. The layout: nodes 0..J-1 are the joints in skeleton order
// with their rest TRS (a joint with a parent offset gets an extra parent node
// holding it as a matrix), then a node with the skinned mesh (one glTF primitive
// per Primitive: POSITION, NORMAL, JOINTS_0 as UNSIGNED_BYTE for up to 256
// joints or else UNSIGNED_SHORT, WEIGHTS_0 float, indices), one skin, one
// animation per action (key times shared between channels that have the same).
// Deterministic: the same character and options give the same bytes.
// Throws std::invalid_argument for a character whose arrays disagree.
std::vector<uint8_t> encode_gltf(const Character& character, const GltfWriteOptions& options = {});

// encode_gltf written to `path`. Throws UsageError naming the path when it
// cannot be written (base/output_file.h).
void write_gltf(const Character& character, const std::string& path, const GltfWriteOptions& options = {});

}  // namespace crowdprof

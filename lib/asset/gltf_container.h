// The first, untrusting read of a glTF file: the bytes, the GLB chunks, the JSON,
// and the checks that must pass before tiny_gltf sees anything (tiny_gltf trusts
// indices inside KHR_draco_mesh_compression and expands paths with wordexp).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/input_file.h"

namespace crowdprof {

// Files larger than this are refused before reading: a character is megabytes.
// The same bound holds for all of a file's buffers together.
inline constexpr uint64_t kMaxAssetBytes = 1ull << 30;

struct GltfContainer {
  std::string path;      // as the user gave it (used in messages)
  std::string base_dir;  // folder that external URIs must stay inside
  bool binary = false;   // GLB
  nlohmann::json json;
  std::string json_text;           // the text `json` was parsed from, handed to tiny_gltf as it is
  std::vector<unsigned char> bin;  // GLB BIN chunk; empty for .gltf
};

// Reads and splits the file and parses its JSON. Throws InputError for a missing
// file, a directory, an empty or non-glTF file, a truncated GLB or broken JSON.
GltfContainer read_gltf_container(const std::string& path);
// The same for a file's bytes already in memory; `path` names it in messages and
// its folder is base_dir.
GltfContainer gltf_container_from_bytes(const std::vector<unsigned char>& bytes, const std::string& path);

// Checks what tiny_gltf would trust (gltf_preflight.cpp): buffer and image URIs
// stay inside base_dir (no absolute paths, no "..", no schemes but data:),
// required extensions are supported, every index names an existing element, buffer
// views lie inside their buffers, and Draco extensions are complete. Throws InputError.
void preflight_gltf(const GltfContainer& container);

// Resolves a relative URI against base_dir, refusing anything that leaves it.
// Returns the absolute path. Throws InputError naming `what` ("buffer 0").
std::string resolve_inside(const GltfContainer& container, const std::string& uri, const std::string& what);

// The files a glTF file reads beside itself (buffers and images by URI), as
// resolved paths: inputs that no output may overwrite. None where the file
// cannot be read or a URI would be refused (loading it says why).
std::vector<std::string> gltf_external_files(const std::string& path);

// An index or count as error messages print it.
inline std::string str(size_t i) {
  return std::to_string(i);
}

}  // namespace crowdprof

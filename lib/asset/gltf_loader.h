// Loading characters from .gltf (external buffers, data URIs) and .glb files,
// with KHR_draco_mesh_compression decoded. Inputs are treated as hostile: every
// failure is an InputError "<file>: <problem>", never a crash or a guess.
#pragma once

#include <string>
#include <vector>

#include "asset/character.h"
#include "base/input_file.h"

namespace crowdprof {

// Everything crowdprof reads from one file.
struct GltfAsset {
  std::string file;
  std::vector<Character> characters;  // one per skin, in the file's skin order
  // Animations as they target nodes (Channel::joint is a node index), for files
  // that animate nodes rather than skins (such as InterpolationTest).
  std::vector<Action> node_actions;
  std::vector<std::string> node_names;
  bool draco_decoded = false;
};

// Loads every skin of the file as a character.
GltfAsset load_gltf(const std::string& file);
// The same for a file's bytes already in memory (the fuzzer's way: no file per
// input). `file` names it in messages; external URIs resolve beside it.
GltfAsset load_gltf_from_memory(const std::vector<unsigned char>& bytes, const std::string& file);

// The index of the skin the spec selects in a loaded asset. InputError when
// there is none, when the index is past the last, or when the file holds
// several skins and the spec chose none.
size_t checked_skin(const GltfAsset& asset, const CharacterSpec& spec);

// Loads the character the spec selects. A file with several skins and no
// "#skin=N" is refused with the list, never resolved silently.
Character load_character(const std::string& spec);

}  // namespace crowdprof

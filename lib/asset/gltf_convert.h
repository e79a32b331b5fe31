// Internal to the loader: turning a checked tinygltf::Model into characters.
#pragma once

#include <string>
#include <vector>

#include "asset/character.h"

namespace tinygltf {
class Model;
}

namespace crowdprof {

// Node graphs deeper than this are refused: real skeletons are tens of levels
// deep, and joint placement walks up through every level.
inline constexpr int kMaxNodeDepth = 1024;

// Key times and values of all actions together, and vertices of one skinned mesh,
// past which a file is refused as absurd (channels and primitives may share one
// accessor, so per-accessor limits alone do not bound them).
inline constexpr size_t kMaxActionFloats = size_t(1) << 26;
inline constexpr size_t kMaxMeshVertices = size_t(1) << 24;

// Parent node of each node (-1 for none). Throws InputError for a child index
// that names no node, a node with two parents, a cycle, or a graph deeper than
// kMaxNodeDepth.
std::vector<int> node_parents(const tinygltf::Model& model, const std::string& file);

// The character that skin `skin` drives: its joints re-ordered parent first, the
// primitives of every mesh node bound to it, and the animations of its joints.
Character convert_skin(const tinygltf::Model& model, const std::vector<int>& parents, int skin,
                       const std::string& file);

// Every animation, with channels targeting node indices.
std::vector<Action> convert_node_actions(const tinygltf::Model& model, const std::string& file);

// Animations restricted to `node_to_joint` (node index -> joint, -1 if none).
std::vector<Action> convert_actions(const tinygltf::Model& model, const std::vector<int>& node_to_joint,
                                    const std::string& file, Fixups* fixups);

}  // namespace crowdprof

// Internal to the loader: turning a checked tinygltf::Model into characters.
#pragma once

#include <string>
#include <vector>

#include "asset/character.h"

namespace tinygltf {
class Model;
}

namespace crowdprof {

// Parent node of each node (-1 for none). Throws InputError for a child index
// that names no node, a node with two parents, or a cycle.
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

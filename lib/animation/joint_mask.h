// The joints an animation layer covers (issue 56): a named joint and every
// joint under it, as a per-joint weight for BlendLayer::joint_weights.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "asset/character.h"

namespace crowdprof {

// weights[j] for every joint of `skeleton`: 0 outside the subtree of the joint
// named `root`; inside it, 1 from `falloff` joints below the root on, and
// rising to it over the first `falloff` (the root (1 / (falloff + 1)), its
// children 2 / (falloff + 1), ...), so a layer laid over the spine eases in
// up the chain instead of breaking at one joint. An empty `root` covers every
// joint at 1. Returns "" or what is wrong: no joint of that name (the joints
// listed), or a falloff below 0.
std::string joint_mask(const Skeleton& skeleton, std::string_view root, int falloff, std::vector<float>* weights);

}  // namespace crowdprof

// What `crowdprof info` says about a file: as text for people, as JSON for scripts.
#pragma once

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "asset/gltf_loader.h"

namespace crowdprof {

// Vertices by number of non-zero influences: [0] one, ..., [3] four.
std::array<size_t, 4> influence_histogram(const SkinnedMesh& mesh);

// Every character of the asset, or with `only_skin` >= 0 only that skin's (a
// valid index: see checked_skin in gltf_loader.h).
nlohmann::json describe_asset(const GltfAsset& asset, int only_skin = -1);
std::string format_asset(const GltfAsset& asset, int only_skin = -1);

}  // namespace crowdprof

// How skinned vertices are written: with ordinary stores, or with non-temporal
// (streaming) stores that send whole cache lines to memory without reading
// them in first and without evicting what the caches hold. A frame whose
// skinned output is far larger than the cache is memory-bound; ordinary stores
// then move each byte twice (the line read for ownership, then written back).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace crowdprof {

enum class OutputStores { Auto, Regular, Streaming };

// Auto streams a frame whose skinned output (float format, every copy's
// vertices x 24 bytes) is larger than this (docs/performance.md, "Streaming
// stores"): output up to the caches' size is read back (digest, GL upload)
// from cache and written fastest with ordinary stores; beyond it, streaming
// wins.
constexpr uint64_t kStreamOutputBytes = uint64_t{64} << 20;

// The policy in force: Auto unless forced (force_output_stores).
OutputStores output_stores();

// Whether a frame writing `frame_output_bytes` of skinned vertices streams
// them under the policy in force.
bool stream_skinned_output(uint64_t frame_output_bytes);

// "auto", "regular" or "streaming".
const char* to_string(OutputStores stores);

// Forces the policy from now on by name ("auto", "regular", "streaming",
// case-insensitive). Returns "" or, changing nothing, why not.
std::string force_output_stores(std::string_view name);

// The environment variable that forces the policy, as --simd's does the target.
constexpr const char* kStoresEnvironmentVariable = "CROWDPROF_STORES";

}  // namespace crowdprof

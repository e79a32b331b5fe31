// Which joint each channel of an action drives, found the two ways the thesis
// compares (§4.2). The BGE before the thesis resolved every animated property
// every frame by its RNA path string, e.g. `pose.bones["Hips"].location`: parse
// the path, then compare the bone name with every bone's name in turn. The
// thesis's bundled lookups resolve each path once and keep the result.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "asset/character.h"

namespace crowdprof {

// The RNA path of what `channel` animates: `pose.bones["<name>"].location`,
// `.rotation_quaternion` or `.scale`, with '"' and '\' in the name escaped by a
// '\' as RNA does. Empty when the channel's joint is not in `skeleton`.
std::string channel_path(const Skeleton& skeleton, const Channel& channel);

// Parses a path of channel_path's form and searches the joint names in order for
// its bone, comparing each (as RNA's BLI_findstring did; no index, no hash).
// Returns the first joint of that name and sets *out_property (when not null),
// or returns -1 when the path is malformed, names an unknown property or no
// joint has that name. Allocates nothing.
int32_t resolve_channel_path(const Skeleton& skeleton, std::string_view path, ChannelPath* out_property);

// One action's paths and, resolved once, the joint each channel drives: the
// targets SamplingJob takes.
struct ActionBindings {
  std::vector<std::string> paths;  // one per channel
  std::vector<int32_t> targets;    // one per channel; -1 when unresolved
};

// The bundled lookup: every path of `action` built and resolved once, by the same
// resolve_channel_path the per-frame lookup uses, so both give the same targets
// (even for duplicate joint names: the first one wins in both).
ActionBindings bind_action(const Skeleton& skeleton, const Action& action);

// The per-frame lookup of master mode: resolves every path of `bindings` again
// into `targets_out` (one slot per path), counting each lookup.
struct ResolvePathsJob {
  const Skeleton* skeleton = nullptr;
  const ActionBindings* bindings = nullptr;
  std::span<int32_t> targets_out;
  size_t* lookups = nullptr;  // incremented once per path resolved; may be null

  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  [[nodiscard]] bool Run() const;
};

}  // namespace crowdprof

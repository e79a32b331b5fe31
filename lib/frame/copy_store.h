// The per-copy arrays of a crowd (data-oriented: one array per field, indexed
// by copy or by pose storage), allocated once when a bench is made; the
// frames write them and allocate nothing. A pose storage is one copy's palette
// and skinned mesh: a copy's own, or with sharing the one its state is held in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "animation/local_pose.h"
#include "animation/sampling.h"
#include "animation/skin_matrix.h"
#include "asset/character.h"
#include "base/modes.h"
#include "frame/prepared_character.h"
#include "scene/crowd.h"
#include "skinning/output_buffer.h"

namespace crowdprof {

struct CopyStore {
  // Allocates every array for `crowd` of `characters`, prepared for `mode`:
  // copies start in their rest pose, their rest vertices in place (with mesh
  // LOD, those of the level `mesh_level` gives each copy; empty: level 0).
  CopyStore(std::span<const Character* const> characters, std::span<const PreparedCharacter> prepared,
            const Crowd& crowd, const ModeSwitches& mode, std::span<const uint8_t> mesh_level = {});

  // Per copy.
  std::vector<float> times;      // this frame's time on its action's clock (Logic)
  std::vector<uint8_t> visible;  // inside the frustum (the last Scenegraph stage)
  std::vector<SamplingCursor> cursors;
  // Transitions (issue 53), per copy; empty without them. The Logic stage
  // writes the action each copy plays now, its weight (< 1 while fading) and
  // the action it fades from with that one's time (frozen: at the change);
  // the pose update keeps the second cursor and pose, and which change each
  // copy's cursors and frozen pose were set for.
  std::vector<uint16_t> actions, from_actions;
  std::vector<float> weights, from_times;
  std::vector<uint32_t> changes, cursor_change, frozen_change;
  std::vector<SamplingCursor> from_cursors;
  std::vector<LocalPose> from_poses;
  std::vector<uint8_t> sampled_twice;  // the last evaluation sampled both actions
  // Layers (--anim-layer): per copy, a cursor per layer of its character
  // (layer L of copy i at layer_cursors[i * kMaxAnimLayers + L]); empty without them.
  std::vector<SamplingCursor> layer_cursors;
  // Per pose storage (one per copy): offsets into palettes and the vertices.
  // Each storage's vertices start on a cache line (whole batches of
  // kSkinBatch vertices), so that skinning can stream whole lines.
  std::vector<size_t> joint_offset, vertex_offset;
  std::vector<float> storage_time;  // the time it was evaluated at (NaN: rest)
  // Transitions: the action and fade weight it was evaluated with (empty without).
  std::vector<uint16_t> storage_action;
  std::vector<float> storage_weight;
  // Per pose slot: one per copy, or one per character with a shared scratch
  // pose (mode master); with per-frame string lookups, each slot's resolved
  // channels at slot_channels[slot] in targets.
  std::vector<LocalPose> poses;
  std::vector<size_t> slot_channels;
  std::vector<int32_t> targets;
  std::vector<SkinMatrix, CacheLineAllocator<SkinMatrix>> palettes;
  // Float vertices (empty when packed); large arrays on huge pages (output_buffer.h).
  std::vector<glm::vec3, CacheLineAllocator<glm::vec3>> positions, normals;
  // Packed vertices (empty when float): 3 position codes and a normal word each.
  std::vector<uint16_t, CacheLineAllocator<uint16_t>> packed_positions;
  std::vector<uint32_t, CacheLineAllocator<uint32_t>> packed_normals;
  bool packed = false;
  // Float vertices skinned on the CPU are written with streaming stores: the
  // frame's output is larger than the caches (skinning/output_stores.h).
  bool stream_output = false;
};

// Bytes a crowd would allocate, to refuse a scene before trying.
uint64_t estimate_bench_bytes(const Character& character, size_t copies, const ModeSwitches& mode);
uint64_t estimate_bench_bytes(std::span<const Character* const> characters, const CrowdOptions& crowd,
                              const ModeSwitches& mode);

}  // namespace crowdprof

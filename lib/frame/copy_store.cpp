#include "frame/copy_store.h"

#include <algorithm>
#include <limits>

#include "animation/pose.h"
#include "skinning/output_stores.h"
#include "skinning/packed_vertex.h"
#include "skinning/skinning.h"

namespace crowdprof {

namespace {

size_t whole_batches(size_t vertices) {
  return (vertices + kSkinBatch - 1) / kSkinBatch * kSkinBatch;
}

// The most channels of any of the character's actions: a pose slot's lookups.
uint64_t max_channels(const Character& c) {
  uint64_t channels = 0;
  for (const Action& a : c.actions) channels = std::max<uint64_t>(channels, a.channels.size());
  return channels;
}

// Copies the GPU skins keep no vertices on the CPU. With uniform palettes a
// character over the bone limit falls back to the CPU, so the estimate keeps them.
bool cpu_vertices(const ModeSwitches& mode) {
  return !skins_on_gpu(mode.skinning) || mode.palettes == PaletteStorage::Uniforms;
}

// What one copy and one pose slot of a character cost.
// `fades`: the copy may change action (transitions).
uint64_t copy_bytes(const Character& c, const ModeSwitches& mode, bool fades) {
  const uint64_t channels = max_channels(c);
  const uint64_t vertex_bytes = !cpu_vertices(mode)                          ? 0
                                : mode.vertex_format == VertexFormat::Packed ? kPackedVertexBytes
                                                                             : kFloatVertexBytes;
  // Transitions: the pose and cursor of the action a copy fades from.
  // Besides: the fade's per-copy words, the two vectors' headers, the
  // schedule's state (scene/transitions.h) and its storage's action and weight.
  const uint64_t fading = fades ? c.skeleton.joint_count() * (sizeof(glm::vec3) * 2 + sizeof(glm::quat)) +
                                      channels * 4 + 32 + sizeof(SamplingCursor) + sizeof(LocalPose) + 56 + 8
                                : 0;
  return c.skeleton.joint_count() * sizeof(SkinMatrix) + whole_batches(c.mesh.vertex_count()) * vertex_bytes +
         channels * 4 + 64 + sizeof(glm::mat4) /* world */ + sizeof(Aabb) + 4 * sizeof(size_t) /* offsets */ + fading;
}
uint64_t slot_bytes(const Character& c) {
  const uint64_t channels = max_channels(c);
  // Model-space matrices are per thread, not per slot: a few KiB in all.
  return c.skeleton.joint_count() * (sizeof(glm::vec3) * 2 + sizeof(glm::quat)) + channels * 4;
}

}  // namespace

uint64_t estimate_bench_bytes(const Character& c, size_t copies, const ModeSwitches& mode) {
  uint64_t slots = mode.pose == PoseStorage::SharedScratch ? 1 : copies;
  return c.shared_bytes() + copies * copy_bytes(c, mode, mode.transitions_s > 0) + slots * slot_bytes(c);
}

uint64_t estimate_bench_bytes(std::span<const Character* const> characters, const CrowdOptions& crowd,
                              const ModeSwitches& mode) {
  uint64_t bytes = 0;
  std::vector<size_t> copies(characters.size(), 0);
  std::vector<uint8_t> fades(characters.size(), mode.transitions_s > 0);
  for (const CrowdGroup& group : crowd_groups(crowd))
    if (group.character < copies.size()) {
      copies[group.character] += group.copies;
      if (group.transitions) fades[group.character] = group.transitions->mean_s > 0;
    }
  for (size_t k = 0; k < characters.size(); ++k) {
    uint64_t slots = mode.pose == PoseStorage::SharedScratch ? 1 : copies[k];
    bytes += characters[k]->shared_bytes() + copies[k] * copy_bytes(*characters[k], mode, fades[k]) +
             slots * slot_bytes(*characters[k]);
  }
  return bytes;
}

CopyStore::CopyStore(std::span<const Character* const> characters, std::span<const PreparedCharacter> prepared,
                     const Crowd& crowd, const ModeSwitches& mode, std::span<const uint8_t> mesh_level) {
  const size_t n = crowd.size();
  times.assign(n, 0.0f);
  visible.assign(n, 0);
  cursors.resize(n);
  joint_offset.resize(n);
  vertex_offset.resize(n);
  storage_time.assign(n, std::numeric_limits<float>::quiet_NaN());
  size_t joints = 0, vertices = 0;
  for (size_t i = 0; i < n; ++i) {
    const PreparedCharacter& p = prepared[crowd.kind[i]];
    joint_offset[i] = joints;
    vertex_offset[i] = vertices;
    joints += p.joints;
    // The GPU skins from the rest mesh it holds: no vertices here (gpu, compute, baked).
    if (!skins_on_gpu(p.site)) vertices += whole_batches(p.vertices);
    const Character& character = *characters[crowd.kind[i]];
    if (!character.actions.empty()) reset_cursor(character.actions[crowd.action[i]], &cursors[i]);
  }
  if (any_layers(prepared)) {
    layer_cursors.resize(n * kMaxAnimLayers);
    for (size_t i = 0; i < n; ++i) {
      const CharacterLayers& layers = prepared[crowd.kind[i]].layers;
      for (size_t l = 0; l < layers.layers.size(); ++l)
        reset_cursor(characters[crowd.kind[i]]->actions[layers.layers[l].action],
                     &layer_cursors[i * kMaxAnimLayers + l]);
    }
  }
  if (!crowd.transitions.empty()) {
    actions = crowd.action;
    from_actions = crowd.action;
    weights.assign(n, 1.0f);
    from_times.assign(n, 0.0f);
    changes.assign(n, 0);
    cursor_change.assign(n, 0);
    frozen_change.assign(n, 0);
    from_cursors.resize(n);
    from_poses.resize(n);
    sampled_twice.assign(n, 0);
    storage_action = crowd.action;
    storage_weight.assign(n, 1.0f);
    for (size_t i = 0; i < n; ++i) reset_to_rest(characters[crowd.kind[i]]->skeleton, &from_poses[i]);
  }
  const bool shared = mode.pose == PoseStorage::SharedScratch;
  const size_t slots = shared ? characters.size() : n;
  poses.resize(slots);
  slot_channels.resize(slots);
  size_t channels = 0;
  for (size_t s = 0; s < slots; ++s) {
    const size_t k = shared ? s : crowd.kind[s];
    reset_to_rest(characters[k]->skeleton, &poses[s]);
    slot_channels[s] = channels;
    channels += prepared[k].max_channels;
  }
  targets.assign(channels, -1);
  palettes.resize(joints);
  packed = mode.vertex_format == VertexFormat::Packed;
  stream_output = !packed && stream_skinned_output(vertices * kFloatVertexBytes);
  positions.resize(packed ? 0 : vertices);
  normals.resize(packed ? 0 : vertices);
  packed_positions.resize(packed ? 3 * vertices : 0);
  packed_normals.resize(packed ? vertices : 0);
  // Until a pose is computed, copies show the rest pose.
  std::vector<std::vector<SkinMatrix>> rest_palettes;
  for (const Character* character : characters) rest_palettes.push_back(rest_palette(*character));
  for (size_t i = 0; i < n; ++i) {
    const size_t level = mesh_level.empty() ? 0 : mesh_level[i];
    const SkinnedMesh& mesh =
        level == 0 ? characters[crowd.kind[i]]->mesh : prepared[crowd.kind[i]].mesh_lods[level - 1].mesh;
    const std::vector<SkinMatrix>& rest = rest_palettes[crowd.kind[i]];
    std::copy(rest.begin(), rest.end(), palettes.begin() + static_cast<std::ptrdiff_t>(joint_offset[i]));
    if (skins_on_gpu(prepared[crowd.kind[i]].site)) continue;
    const size_t v0 = vertex_offset[i];
    if (packed) {
      const PositionQuantisation& q = prepared[crowd.kind[i]].quantisation;
      for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        quantise_position(q, mesh.positions[v], &packed_positions[3 * (v0 + v)]);
        packed_normals[v0 + v] = pack_normal(mesh.normals[v]);
      }
      continue;
    }
    std::copy(mesh.positions.begin(), mesh.positions.end(), positions.begin() + static_cast<std::ptrdiff_t>(v0));
    std::copy(mesh.normals.begin(), mesh.normals.end(), normals.begin() + static_cast<std::ptrdiff_t>(v0));
  }
}

}  // namespace crowdprof

// Animation layers on a copy's pose (issue 56, --anim-layer): a character's
// layers resolved once from the switch (actions by index, masks per joint,
// additive references), and the job that lays them over the copy's own pose
// or crossfade in one blend (blending.h).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "animation/binding.h"
#include "animation/blending.h"
#include "asset/character.h"
#include "base/anim_layers.h"

namespace crowdprof {

// At most this many layers: the job builds its blend on the stack.
inline constexpr size_t kMaxAnimLayers = 8;

struct CharacterLayers {
  struct Layer {
    size_t action = 0;
    float weight = 1.0f;
    bool additive = false;
    std::vector<float> mask;  // per joint: the layer's share there (1 everywhere without a mask)
    LocalPose reference;      // additive: the action at its first frame, the delta's zero
  };
  std::vector<Layer> layers;  // those of weight > 0, in the switch's order
  // Per joint, what the copy's own pose keeps: 1 - the override layers'
  // weights there (at least 0); empty when no layer overrides.
  std::vector<float> own_mask;

  bool empty() const { return layers.empty(); }
};

// `specs` against the character's actions (by name) and joints. Returns "" or
// what is wrong, naming the action or joint and listing the character's; a
// layer of weight 0 is left out (the copy shows its own pose bit for bit).
std::string resolve_layers(const Character& character, std::span<const ActionBindings> bindings,
                           std::span<const AnimLayer> specs, CharacterLayers* out);

// The time a layer's action shows when the copy's own action is at `time`:
// as far into it as the copy is into its own, wrapped to the layer's length.
// Copies at one time show one layered pose, so sharing and held poses need
// nothing more to match.
float layer_time(const Action& own, float time, const Action& layer);

struct LayeringJob {
  const CharacterLayers* layers = nullptr;
  // The copy's own: its pose at weight 1, or a crossfade's two poses.
  std::span<const BlendLayer> own;
  std::span<const LocalPose> layer_poses;  // one per layer, its action at layer_time
  std::span<LocalPose> deltas;             // scratch, one per layer (additive ones are written)
  const LocalPose* rest = nullptr;
  LocalPose* output = nullptr;  // may be one of `own`'s poses

  // Layers set and not empty, at most kMaxAnimLayers of them; 1 or 2 own
  // poses; a pose and a delta per layer; rest and output set.
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing once `deltas`
  // have held poses of this skeleton.
  [[nodiscard]] bool Run() const;
};

}  // namespace crowdprof

// Animation layers (issue 56): actions laid over what a copy plays, on the
// joints under a named joint (a mask) or added as a delta, as the BGE's action
// layers (blend or add) and ozz's BlendingJob layers do. The words of the
// switch --anim-layer; the animation stage resolves names to a character's
// actions and joints (animation/layering.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace crowdprof {

enum class LayerBlend : unsigned char {
  Override,  // replaces the layers below by its weight on its joints
  Add,       // adds its action's motion since the action's first frame
};

struct AnimLayer {
  std::string action;   // a name of the character's actions
  std::string mask;     // a joint: the layer covers it and the joints under it; empty: every joint
  double weight = 1.0;  // 0 to 1
  int falloff = 0;      // joints down from the mask's joint over which the weight eases in
  LayerBlend blend = LayerBlend::Override;

  bool operator==(const AnimLayer&) const = default;
};

// "action=wave,mask=spine_01,weight=0.8,falloff=2,blend=override", the keys
// in any order, only action required; layers apart by ';' (as several
// --anim-layer options join). Returns "" or what is wrong ("blend: expected
// override or add"); `layers` is set only when all is right. An empty text is
// no layer.
std::string parse_anim_layers(std::string_view text, std::vector<AnimLayer>* layers);

// The layers as parse_anim_layers reads them back: every key, in the order
// above, layers apart by ';'.
std::string anim_layers_text(const std::vector<AnimLayer>& layers);

std::string_view to_string(LayerBlend blend);  // "override", "add"

}  // namespace crowdprof

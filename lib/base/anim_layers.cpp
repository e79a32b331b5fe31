#include "base/anim_layers.h"

#include <cmath>

#include "base/number_text.h"

namespace crowdprof {

namespace {

// One layer's "key=value,..." into `layer`; "" or what is wrong.
std::string parse_one_layer(std::string_view text, AnimLayer* layer) {
  AnimLayer parsed;
  bool has_action = false;
  while (!text.empty()) {
    const size_t comma = text.find(',');
    const std::string_view field = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    const size_t equals = field.find('=');
    if (equals == std::string_view::npos)
      return "'" + std::string(field) + "': expected KEY=VALUE (keys action, mask, weight, falloff, blend)";
    const std::string_view key = field.substr(0, equals), value = field.substr(equals + 1);
    if (key == "action") {
      if (value.empty()) return "action: expected the name of one of the character's actions";
      parsed.action = value;
      has_action = true;
    } else if (key == "mask") {
      parsed.mask = value;
    } else if (key == "weight") {
      const std::optional<double> w = parse_number(value);
      if (!w || *w < 0 || *w > 1) return "weight: expected a number from 0 to 1";
      parsed.weight = *w;
    } else if (key == "falloff") {
      const std::optional<double> n = parse_number(value);
      if (!n || *n < 0 || *n > 64 || std::floor(*n) != *n) return "falloff: expected a whole number of joints, 0 to 64";
      parsed.falloff = static_cast<int>(*n);
    } else if (key == "blend") {
      if (value == "override")
        parsed.blend = LayerBlend::Override;
      else if (value == "add")
        parsed.blend = LayerBlend::Add;
      else
        return "blend: expected override or add";
    } else {
      return "no key '" + std::string(key) + "' (the keys are action, mask, weight, falloff, blend)";
    }
  }
  if (!has_action) return "a layer needs action=NAME";
  *layer = parsed;
  return {};
}

}  // namespace

std::string parse_anim_layers(std::string_view text, std::vector<AnimLayer>* layers) {
  std::vector<AnimLayer> parsed;
  while (!text.empty()) {
    const size_t semicolon = text.find_first_of(";\n");
    const std::string_view one = text.substr(0, semicolon);
    text = semicolon == std::string_view::npos ? std::string_view() : text.substr(semicolon + 1);
    if (one.empty()) continue;
    AnimLayer layer;
    if (std::string problem = parse_one_layer(one, &layer); !problem.empty()) {
      return parsed.empty() && text.empty() ? problem : "layer " + std::to_string(parsed.size() + 1) + ": " + problem;
    }
    parsed.push_back(std::move(layer));
  }
  *layers = std::move(parsed);
  return {};
}

std::string anim_layers_text(const std::vector<AnimLayer>& layers) {
  std::string text;
  for (const AnimLayer& l : layers)
    text += (text.empty() ? "" : ";") + std::string("action=") + l.action + (l.mask.empty() ? "" : ",mask=" + l.mask) +
            ",weight=" + shortest_text(l.weight) + ",falloff=" + std::to_string(l.falloff) +
            ",blend=" + std::string(to_string(l.blend));
  return text;
}

std::string_view to_string(LayerBlend blend) {
  return blend == LayerBlend::Override ? "override" : "add";
}

}  // namespace crowdprof

#include "base/switch_table.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

#include "base/number_text.h"

namespace crowdprof {

namespace {

using nlohmann::json;

std::string shortest(float value) {
  char text[32];
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(value));
    if (std::strtof(text, nullptr) == value) break;
  }
  return text;
}

std::string set_on_off(bool& field, std::string_view text) {
  if (text == "on")
    field = true;
  else if (text == "off")
    field = false;
  else
    return "expected on or off";
  return {};
}

// One of an enum's names; the names in `choices` are also what to_string gives.
template <typename Enum, size_t N>
std::string set_choice(Enum& field, std::string_view text, const std::array<Enum, N>& choices) {
  std::string names;
  for (Enum e : choices) {
    if (text == to_string(e)) {
      field = e;
      return {};
    }
    names += (names.empty() ? "" : ", ") + std::string(to_string(e));
  }
  return "expected one of " + names;
}

constexpr std::array kLookups = {Lookups::PerFrameString, Lookups::Bundled};
constexpr std::array kPoses = {PoseStorage::SharedScratch, PoseStorage::PerCopy};
constexpr std::array kSites = {SkinningSite::CpuInRasterizer, SkinningSite::CpuInAnimations, SkinningSite::Gpu,
                               SkinningSite::Compute, SkinningSite::Baked};
constexpr std::array kFormats = {VertexFormat::Float, VertexFormat::Packed};
constexpr std::array kPalettes = {PaletteStorage::Uniforms, PaletteStorage::Buffer};
constexpr std::array kDraws = {DrawMethod::PerCopy, DrawMethod::Instanced};
constexpr std::array kFrustumTests = {FrustumTest::Cpu, FrustumTest::Gpu};
constexpr std::array kIndexOrders = {IndexOrder::File, IndexOrder::Optimized};
constexpr std::array kCrossfades = {Crossfade::Frozen, Crossfade::Sampled};

// Seconds from 0 to 3600; `what` names the value in the message.
std::string set_seconds(double& field, std::string_view text, const char* what) {
  std::optional<double> value = parse_number(text);
  if (!value || !(*value >= 0 && *value <= 3600)) return std::string("expected ") + what;
  field = *value;
  return {};
}

// Seconds, as a decimal or a fraction 1/N.
std::string set_share_quantum(ModeSwitches& s, std::string_view text) {
  std::optional<double> value;
  size_t slash = text.find('/');
  if (slash == std::string_view::npos) {
    value = parse_number(text);
  } else {
    std::optional<double> top = parse_number(text.substr(0, slash)), bottom = parse_number(text.substr(slash + 1));
    if (top && bottom && *bottom > 0) value = *top / *bottom;
  }
  if (!value || *value < 0 || *value > 10) return "expected seconds from 0 to 10, e.g. 1/30 or 0.05";
  s.share_quantum_s = *value;
  return {};
}

// Three shares of the screen's height, A,B,C with 1 >= A >= B >= C >= 0.
std::string set_lod_thresholds_into(LodThresholds& lod, std::string_view text) {
  std::optional<double> v[3];
  size_t first = text.find(','), second = first == std::string_view::npos ? first : text.find(',', first + 1);
  if (second != std::string_view::npos && text.find(',', second + 1) == std::string_view::npos) {
    v[0] = parse_number(text.substr(0, first));
    v[1] = parse_number(text.substr(first + 1, second - first - 1));
    v[2] = parse_number(text.substr(second + 1));
  }
  if (!v[0] || !v[1] || !v[2] || !(*v[0] <= 1 && *v[0] >= *v[1] && *v[1] >= *v[2] && *v[2] >= 0))
    return "expected three shares of the screen's height A,B,C with 1 >= A >= B >= C >= 0";
  lod = {static_cast<float>(*v[0]), static_cast<float>(*v[1]), static_cast<float>(*v[2])};
  return {};
}

std::string set_lod_thresholds(ModeSwitches& s, std::string_view text) {
  return set_lod_thresholds_into(s.lod, text);
}

std::string set_mesh_lod_thresholds(ModeSwitches& s, std::string_view text) {
  LodThresholds parsed;
  if (!set_lod_thresholds_into(parsed, text).empty())
    return "expected three shares of the screen's height A,B,C with 1 >= A >= B >= C >= 0";
  s.mesh_lod_at = {parsed.every_1, parsed.every_2, parsed.every_4};
  return {};
}

std::string set_passes(ModeSwitches& s, std::string_view text) {
  std::optional<double> value = parse_number(text);
  // The range first: a double outside uint32_t's is undefined to convert.
  if (!value || !(*value >= 1 && *value <= kMaxPasses) || *value != std::floor(*value))
    return "expected 1 to " + std::to_string(kMaxPasses) +
           " (1: colour; 2: depth prepass and colour; more: " + "shadow cascades between them)";
  s.passes = static_cast<uint32_t>(*value);
  return {};
}

std::string set_anim_budget(ModeSwitches& s, std::string_view text) {
  std::optional<double> value = parse_number(text);
  if (!value || *value < 0 || *value > 10000) return "expected milliseconds from 0 (no budget) to 10000";
  s.anim_budget_ms = *value;
  return {};
}

const std::array kSwitches = {
    SwitchSpec{"lookups", "string|bundled",
               "string: every channel found by its path every frame (the BGE's); bundled: resolved once at load (4.2)",
               [](const ModeSwitches& s) { return json(to_string(s.lookups)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.lookups, t, kLookups); }},
    SwitchSpec{"culling", "on|off", "Animation culling (4.1): copies off-screen get no pose update and no skinning",
               [](const ModeSwitches& s) { return json(s.animation_culling); },
               [](ModeSwitches& s, std::string_view t) { return set_on_off(s.animation_culling, t); }},
    SwitchSpec{"pose", "shared|per-copy", "shared: one scratch pose every copy is sampled into (the BGE's); per-copy",
               [](const ModeSwitches& s) { return json(to_string(s.pose)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.pose, t, kPoses); }},
    SwitchSpec{"parallel", "on|off", "Pose updates (and CPU skinning in Animations) over copies on oneTBB (4.3)",
               [](const ModeSwitches& s) { return json(s.parallel); },
               [](ModeSwitches& s, std::string_view t) { return set_on_off(s.parallel, t); }},
    SwitchSpec{"skinning", "rasterizer|animations|gpu|compute|baked",
               "Where vertices are skinned: on the CPU counted in Rasterizer (the BGE's) or in Animations, in the "
               "vertex shader (4.4), by a compute pass, or from actions baked at load",
               [](const ModeSwitches& s) { return json(to_string(s.skinning)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.skinning, t, kSites); }},
    SwitchSpec{"palettes", "uniforms|buffer",
               "For skinning on the GPU: a uniform array per draw (128 bones at most) or one shader storage buffer "
               "(no bone limit)",
               [](const ModeSwitches& s) { return json(to_string(s.palettes)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.palettes, t, kPalettes); }},
    SwitchSpec{"draw", "per-copy|instanced", "A draw call per copy, or one per character kind (needs palettes buffer)",
               [](const ModeSwitches& s) { return json(to_string(s.draw)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.draw, t, kDraws); }},
    SwitchSpec{"vertex_format", "float|packed",
               "What CPU skinning writes for the GPU: float (32-bit positions and normals, 24 bytes a vertex) or "
               "packed (16-bit positions in the character's box, 10:10:10:2 normals, 10 bytes)",
               [](const ModeSwitches& s) { return json(to_string(s.vertex_format)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.vertex_format, t, kFormats); }, false},
    SwitchSpec{"share", "on|off",
               "Animation sharing: copies in the same action and time share one pose and one skinned mesh",
               [](const ModeSwitches& s) { return json(s.share_poses); },
               [](ModeSwitches& s, std::string_view t) { return set_on_off(s.share_poses, t); }, false},
    SwitchSpec{"share_quantum", "SECONDS",
               "With share on: snap each copy's time to a multiple of this many seconds (e.g. 1/30 or 0.05) so "
               "copies fall into shared states; 0: exact times",
               [](const ModeSwitches& s) { return json(s.share_quantum_s); }, set_share_quantum, false},
    SwitchSpec{"update_lod", "on|off",
               "Update-rate LOD: copies updated every 1, 2, 4 or 8 frames by size on screen, holding their pose "
               "between",
               [](const ModeSwitches& s) { return json(s.update_lod); },
               [](ModeSwitches& s, std::string_view t) { return set_on_off(s.update_lod, t); }, false},
    SwitchSpec{"lod_thresholds", "A,B,C",
               "Shares of the screen's height at which a copy is updated every frame (>= A), every 2nd (>= B), every "
               "4th (>= C), else every 8th",
               [](const ModeSwitches& s) {
                 return json(shortest(s.lod.every_1) + "," + shortest(s.lod.every_2) + "," + shortest(s.lod.every_4));
               },
               set_lod_thresholds, false},
    SwitchSpec{"anim_budget", "MS",
               "Keep the Animations category's p95 at or under this many milliseconds by updating the copies "
               "smallest on screen less often (at least every 64 frames); 0: no budget",
               [](const ModeSwitches& s) { return json(s.anim_budget_ms); }, set_anim_budget, false},
    SwitchSpec{"passes", "N",
               "Draws of the crowd a frame, each into its own target: 1, colour only; 2, a depth prepass and "
               "colour; N > 2, the prepass, N-2 shadow cascades (2048x2048 depth maps) and colour. Vertex-shader "
               "skinning repeats per pass, compute skinning does not. Needs a GL backend",
               [](const ModeSwitches& s) { return json(s.passes); }, set_passes, false},
    SwitchSpec{"frustum", "cpu|gpu",
               "Where copies are tested against the camera and the draws listed: cpu, every copy's box each frame in "
               "Scenegraph; gpu, a compute pass culls and writes indirect draws, so the CPU's work per frame does "
               "not grow with the crowd (needs skinning baked)",
               [](const ModeSwitches& s) { return json(to_string(s.frustum)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.frustum, t, kFrustumTests); }, false},
    SwitchSpec{"mesh_lod", "on|off",
               "Mesh LOD: copies small on screen skin and draw a simplified mesh (half, a quarter, a tenth of the "
               "triangles, made at load with meshoptimizer); needs share off",
               [](const ModeSwitches& s) { return json(s.mesh_lod); },
               [](ModeSwitches& s, std::string_view t) { return set_on_off(s.mesh_lod, t); }, false},
    SwitchSpec{"mesh_lod_thresholds", "A,B,C",
               "Shares of the screen's height under which a copy draws mesh level 1 (< A), 2 (< B), 3 (< C); it "
               "refines again 15% above a threshold",
               [](const ModeSwitches& s) {
                 return json(shortest(s.mesh_lod_at.level_1) + "," + shortest(s.mesh_lod_at.level_2) + "," +
                             shortest(s.mesh_lod_at.level_3));
               },
               set_mesh_lod_thresholds, false},
    SwitchSpec{"index_order", "file|optimized",
               "The order the GPU gets each mesh's triangles in: file, as the file lists them; optimized, "
               "meshoptimizer's vertex-cache order, so the GPU shades each vertex about once (the vertices keep "
               "the order skinning batches them in). Results without it ran in file order",
               [](const ModeSwitches& s) { return json(to_string(s.index_order)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.index_order, t, kIndexOrders); }, false,
               "file"},
    SwitchSpec{"transitions", "SECONDS",
               "Each copy changes to another action of its character after an interval drawn from the seed around "
               "this mean (half to one and a half times it), fading in over --blend-in; with --actions shared a "
               "group changes as one; a character of one action re-enters it at a new phase. 0: no changes",
               [](const ModeSwitches& s) { return json(s.transitions_s); },
               [](ModeSwitches& s, std::string_view t) {
                 // A floor, so that a frame never holds more than a few changes of a copy.
                 double value = 0;
                 std::string problem = set_seconds(value, t, "0 (no changes) or seconds from 0.05 to 3600");
                 if (problem.empty() && value > 0 && value < 0.05)
                   problem = "expected 0 (no changes) or seconds from 0.05 to 3600";
                 if (problem.empty()) s.transitions_s = value;
                 return problem;
               },
               false},
    SwitchSpec{
        "blend_in", "SECONDS",
        "With transitions: how long a copy fades from its last action into its next (at most half of "
        "--transitions); 0 snaps",
        [](const ModeSwitches& s) { return json(s.blend_in_s); },
        [](ModeSwitches& s, std::string_view t) { return set_seconds(s.blend_in_s, t, "seconds from 0 to 3600"); },
        false},
    SwitchSpec{"crossfade", "frozen|sampled",
               "With transitions: frozen fades toward the pose held when the change came, one action sampled a "
               "frame (the BGE's); sampled samples both actions every frame of the fade (blend trees': ozz, Unreal)",
               [](const ModeSwitches& s) { return json(to_string(s.crossfade)); },
               [](ModeSwitches& s, std::string_view t) { return set_choice(s.crossfade, t, kCrossfades); }, false},
    SwitchSpec{"anim_layer",
               "LAYER",
               "An action laid over each copy's, LAYER being action=NAME[,mask=JOINT][,weight=W (1)][,falloff=N "
               "(0)][,blend=override|add] (repeat for more layers, or join them with ';'): override takes its "
               "weight on the joint named by mask and the joints under it (every joint without a mask), easing in "
               "over falloff joints down the chain; add adds its motion since its first frame. Plays on the copy's "
               "clock (the action's time, wrapped to the layer's length). See crowdprof info for joint names",
               [](const ModeSwitches& s) { return json(anim_layers_text(s.anim_layers)); },
               [](ModeSwitches& s, std::string_view t) { return parse_anim_layers(t, &s.anim_layers); },
               false,
               {},
               true},
};

}  // namespace

std::span<const SwitchSpec> switch_table() {
  return kSwitches;
}

const SwitchSpec* find_switch(std::string_view name) {
  for (const SwitchSpec& spec : kSwitches)
    if (spec.name == name) return &spec;
  return nullptr;
}

std::string switch_names() {
  std::string names;
  for (const SwitchSpec& spec : kSwitches) names += (names.empty() ? "" : ", ") + std::string(spec.name);
  return names;
}

std::string option_spelling(std::string_view name) {
  std::string option = "--" + std::string(name);
  for (char& c : option)
    if (c == '_') c = '-';
  return option;
}

std::string switch_text(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "on" : "off";
  if (value.is_number_integer()) return value.dump();
  if (value.is_number()) return shortest_text(value.get<double>());
  return value.dump();
}

std::string readable_switch_text(const json& value) {
  if (!value.is_number_float() || value.get<double>() == std::floor(value.get<double>())) return switch_text(value);
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value.get<double>());
  return std::string(text).find('e') == std::string::npos ? text : switch_text(value);
}

std::pair<std::string, std::string> switch_differences(const ModeSwitches& a, const ModeSwitches& b) {
  std::pair<std::string, std::string> texts;
  for (const SwitchSpec& spec : kSwitches) {
    json va = spec.get(a), vb = spec.get(b);
    if (va == vb) continue;
    std::string ta = readable_switch_text(va), tb = readable_switch_text(vb);
    if (ta == tb) ta = switch_text(va), tb = switch_text(vb);  // apart beyond 3 digits
    std::string option = option_spelling(spec.name);
    texts.first += (texts.first.empty() ? "" : ", ") + option + " " + ta;
    texts.second += (texts.second.empty() ? "" : ", ") + option + " " + tb;
  }
  return texts;
}

std::string switch_text(const SwitchSpec& spec, const ModeSwitches& s) {
  return switch_text(spec.get(s));
}

json switches_to_json(const ModeSwitches& s) {
  const ModeSwitches plain;
  json switches = json::object();
  for (const SwitchSpec& spec : kSwitches) {
    json value = spec.get(s);
    if (spec.always_recorded || !spec.when_absent.empty() || value != spec.get(plain))
      switches[std::string(spec.name)] = std::move(value);
  }
  return switches;
}

std::string switches_from_json(const json& switches, ModeSwitches& s) {
  if (!switches.is_object()) return "expected an object of switches";
  s = ModeSwitches{};
  for (const SwitchSpec& spec : kSwitches)
    if (!spec.when_absent.empty() && !switches.contains(std::string(spec.name))) spec.set(s, spec.when_absent);
  for (const auto& [name, value] : switches.items()) {
    const SwitchSpec* spec = find_switch(name);
    if (!spec) return "no switch '" + name + "' (the switches are " + switch_names() + ")";
    if (!value.is_string() && !value.is_boolean() && !value.is_number())
      return name + ": expected a string, true/false or a number";
    if (std::string problem = spec->set(s, switch_text(value)); !problem.empty()) return name + ": " + problem;
  }
  return {};
}

std::string preset_values(const SwitchSpec& spec) {
  // Presets grouped by value, the largest group last as "the others".
  std::vector<std::pair<std::string, std::string>> groups;  // value, presets
  for (const ModePreset& preset : mode_presets()) {
    std::string value = readable_switch_text(spec.get(preset.switches));
    if (value.empty()) value = "none";
    auto group = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == value; });
    if (group == groups.end())
      groups.push_back({value, std::string(preset.name)});
    else
      group->second += ", " + std::string(preset.name);
  }
  if (groups.size() == 1) return groups.front().first + " in every mode";
  auto count = [](const std::string& names) { return std::count(names.begin(), names.end(), ',') + 1; };
  std::stable_sort(groups.begin(), groups.end(),
                   [&](const auto& a, const auto& b) { return count(a.second) < count(b.second); });
  std::string text;
  for (size_t g = 0; g + 1 < groups.size(); ++g) text += groups[g].first + " in " + groups[g].second + "; ";
  return text + groups.back().first + " in the others";
}

}  // namespace crowdprof

#include "base/modes.h"

#include <array>
#include <sstream>

namespace crowdprof {

namespace {

// The thesis's switches; the rest keep their defaults (off).
constexpr ModeSwitches thesis(Lookups lookups, bool culling, PoseStorage pose, bool parallel, SkinningSite skinning) {
  ModeSwitches s;
  s.lookups = lookups;
  s.animation_culling = culling;
  s.pose = pose;
  s.parallel = parallel;
  s.skinning = skinning;
  return s;
}

constexpr ModeSwitches kMaster =
    thesis(Lookups::PerFrameString, false, PoseStorage::SharedScratch, false, SkinningSite::CpuInRasterizer);
constexpr ModeSwitches kCulled =
    thesis(Lookups::PerFrameString, true, PoseStorage::SharedScratch, false, SkinningSite::CpuInRasterizer);
constexpr ModeSwitches kThreaded =
    thesis(Lookups::Bundled, true, PoseStorage::PerCopy, true, SkinningSite::CpuInAnimations);
constexpr ModeSwitches kHwskin = thesis(Lookups::Bundled, true, PoseStorage::PerCopy, true, SkinningSite::Gpu);
// A preset that is `base` with one switch changed: each mode below is the one
// before it plus one idea.
template <typename Value>
constexpr ModeSwitches with(ModeSwitches base, Value ModeSwitches::*which, Value value) {
  base.*which = value;
  return base;
}

// Beyond the thesis: hwskin with its palettes in a shader storage buffer, then
// also drawn instanced.
constexpr ModeSwitches kBuffer = with(kHwskin, &ModeSwitches::palettes, PaletteStorage::Buffer);
constexpr ModeSwitches kInstanced = with(kBuffer, &ModeSwitches::draw, DrawMethod::Instanced);
// threaded, and copies in the same (action, time) share one pose and one mesh.
constexpr ModeSwitches kShared = with(kThreaded, &ModeSwitches::share_poses, true);
// shared with times snapped to 1/30 s and 2 ms for Animations. No fixed LOD:
// the budget slows the smallest copies only when the time needs it, so copies
// keep every frame's pose while it fits (--update-lod on adds the LOD's floor).
constexpr ModeSwitches kBudget =
    with(with(kShared, &ModeSwitches::share_quantum_s, 1.0 / 30.0), &ModeSwitches::anim_budget_ms, 2.0);
// Skinned by a compute pass from palettes in a storage buffer, drawn per copy;
// baked: every copy of a character in one instanced draw, reading baked tables.
constexpr ModeSwitches kCompute = with(kBuffer, &ModeSwitches::skinning, SkinningSite::Compute);
constexpr ModeSwitches kBaked = with(kInstanced, &ModeSwitches::skinning, SkinningSite::Baked);

constexpr std::array<ModePreset, 10> kPresets = {{
    {"master",
     "the BGE before the thesis: string lookups every frame, every copy posed, one thread, "
     "skinning in the render stage",
     kMaster},
    {"culled", "master plus animation culling: copies off-screen get no pose update and no skinning (4.1)", kCulled},
    {"threaded", "culled plus bundled lookups (4.2) and pose updates and skinning in parallel (4.3)", kThreaded},
    {"hwskin", "threaded, with skinning in the vertex shader (4.4; needs a GL backend)", kHwskin},
    {"buffer", "hwskin with every copy's palette in one shader storage buffer: no 128-bone limit", kBuffer},
    {"instanced", "buffer, drawn with one instanced draw call per character kind and material", kInstanced},
    {"shared",
     "threaded plus animation sharing: one pose and one skinned mesh per (action, time), drawn by every "
     "copy in that state",
     kShared},
    {"budget",
     "shared with times snapped to 1/30 s, and Animations kept under 2 ms by updating the copies "
     "smallest on screen less often (every 2nd to 64th frame, held between) when it needs to",
     kBudget},
    {"compute",
     "threaded's poses, skinned by a compute shader into a vertex buffer, then one plain draw per copy "
     "(as UPBGE and Unreal's GPU skin cache; no bone limit)",
     kCompute},
    {"baked",
     "actions baked into bone matrices at load; per frame each copy sends only its action and time, and the "
     "vertex shader interpolates and skins, one instanced draw per character (no bone limit)",
     kBaked},
}};

}  // namespace

std::span<const ModePreset> mode_presets() {
  return kPresets;
}

const ModePreset* find_mode(std::string_view name) {
  for (const ModePreset& preset : kPresets)
    if (preset.name == name) return &preset;
  return nullptr;
}

std::string mode_names() {
  std::string names;
  for (const ModePreset& preset : kPresets) names += (names.empty() ? "" : ", ") + std::string(preset.name);
  return names;
}

SettingText conflicts(const ModeSwitches& s) {
  if (s.parallel && s.pose == PoseStorage::SharedScratch)
    return "a shared scratch pose (the BGE's bPose swap) cannot be filled by several threads: use {pose} per-copy";
  if (s.palettes == PaletteStorage::Buffer && !skins_on_gpu(s.skinning))
    return "{palettes} buffer holds the palettes the GPU skins with: it needs {skinning} gpu, compute or baked";
  if ((s.skinning == SkinningSite::Compute || s.skinning == SkinningSite::Baked) &&
      s.palettes != PaletteStorage::Buffer)
    return "{skinning} " + std::string(to_string(s.skinning)) +
           " reads its matrices from shader storage buffers: it needs {palettes} buffer";
  if (s.skinning == SkinningSite::Compute && s.draw == DrawMethod::Instanced)
    return "{skinning} compute draws each copy from its own skinned vertices: it needs {draw} per-copy";
  if (s.skinning == SkinningSite::Baked && s.draw == DrawMethod::PerCopy)
    return "{skinning} baked draws every copy of a character in one instanced draw: it needs {draw} instanced";
  if (s.draw == DrawMethod::Instanced && s.skinning != SkinningSite::Gpu && s.skinning != SkinningSite::Baked)
    return "{draw} instanced draws copies that the GPU skins (CPU-skinned copies each have their own vertices): "
           "it needs {skinning} gpu or baked";
  if (s.draw == DrawMethod::Instanced && s.palettes != PaletteStorage::Buffer)
    return "{draw} instanced reads each instance's palette from a buffer: it needs {palettes} buffer";
  if (s.share_poses && (s.skinning == SkinningSite::Compute || s.skinning == SkinningSite::Baked))
    return "{share} on shares the poses the CPU builds: skinning " + std::string(to_string(s.skinning)) +
           " is not measured with it";
  if (s.frustum == FrustumTest::Gpu && s.skinning != SkinningSite::Baked)
    return "{frustum} gpu culls in a compute pass that also writes each visible copy's baked sample and time, so "
           "the CPU touches no copy: it needs {skinning} baked";
  if (s.mesh_lod && s.share_poses)
    return "{mesh_lod} on skins each copy at the level its size picks; copies sharing one skinned mesh may differ "
           "in size: it needs {share} off";
  if (!s.anim_layers.empty() && s.skinning == SkinningSite::Baked)
    return "{anim_layer} lays actions over each copy's pose; {skinning} baked draws poses baked per action, "
           "which a layer cannot change: layers run in every mode but baked (master, culled, threaded, hwskin, buffer, "
           "instanced, shared, budget, compute)";
  if (s.share_quantum_s > 0 && !s.share_poses)
    return "{share_quantum} snaps times so that copies share poses: it needs {share} on";
  if (s.transitions_s > 0 && s.blend_in_s > 0.5 * s.transitions_s) {
    auto seconds = [](double value) {
      std::ostringstream text;
      text << value << " s";
      return text.str();
    };
    return "{blend_in} " + seconds(s.blend_in_s) + (s.blend_in_s == 0.25 ? " (the default)" : "") +
           " is more than half of {transitions} " + seconds(s.transitions_s) +
           ": a copy's fades must not overlap (changes come after at least half the mean); give {blend_in} " +
           seconds(0.5 * s.transitions_s) + " or less";
  }
  if (s.transitions_s > 0 && s.frustum == FrustumTest::Gpu)
    return "{frustum} gpu times each copy in its cull pass from a clock fixed at load, which knows no changes of "
           "action: {transitions} need {frustum} cpu (skinning baked fades there)";
  return {};
}

std::string_view to_string(Lookups lookups) {
  return lookups == Lookups::PerFrameString ? "string" : "bundled";
}
std::string_view to_string(PoseStorage pose) {
  return pose == PoseStorage::SharedScratch ? "shared" : "per-copy";
}
std::string_view to_string(SkinningSite site) {
  switch (site) {
    case SkinningSite::CpuInRasterizer:
      return "rasterizer";
    case SkinningSite::CpuInAnimations:
      return "animations";
    case SkinningSite::Gpu:
      return "gpu";
    case SkinningSite::Compute:
      return "compute";
    case SkinningSite::Baked:
      return "baked";
  }
  return "?";
}

std::string_view to_string(VertexFormat format) {
  return format == VertexFormat::Packed ? "packed" : "float";
}
std::string_view to_string(PaletteStorage palettes) {
  return palettes == PaletteStorage::Uniforms ? "uniforms" : "buffer";
}
std::string_view to_string(FrustumTest frustum) {
  return frustum == FrustumTest::Gpu ? "gpu" : "cpu";
}
std::string_view to_string(Crossfade crossfade) {
  return crossfade == Crossfade::Frozen ? "frozen" : "sampled";
}
std::string_view to_string(IndexOrder order) {
  return order == IndexOrder::File ? "file" : "optimized";
}
std::string_view to_string(DrawMethod draw) {
  return draw == DrawMethod::PerCopy ? "per-copy" : "instanced";
}

}  // namespace crowdprof

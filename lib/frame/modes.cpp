#include "frame/modes.h"

#include <array>

namespace crowdprof {

namespace {

constexpr ModeSwitches kMaster{Lookups::PerFrameString, false, PoseStorage::SharedScratch, false,
                               SkinningSite::CpuInRasterizer};
constexpr ModeSwitches kCulled{Lookups::PerFrameString, true, PoseStorage::SharedScratch, false,
                               SkinningSite::CpuInRasterizer};
constexpr ModeSwitches kThreaded{Lookups::Bundled, true, PoseStorage::PerCopy, true, SkinningSite::CpuInAnimations};
constexpr ModeSwitches kHwskin{Lookups::Bundled, true, PoseStorage::PerCopy, true, SkinningSite::Gpu};

constexpr std::array<ModePreset, 4> kPresets = {{
    {"master", "the BGE before the thesis: string lookups every frame, every copy posed, one thread, "
               "skinning in the render stage",
     kMaster},
    {"culled", "master plus animation culling: copies off-screen get no pose update and no skinning (4.1)", kCulled},
    {"threaded", "culled plus bundled lookups (4.2) and pose updates and skinning in parallel (4.3)", kThreaded},
    {"hwskin", "threaded, with skinning in the vertex shader (4.4; needs a GL backend)", kHwskin},
}};

}  // namespace

std::span<const ModePreset> mode_presets() { return kPresets; }

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

std::string conflicts(const ModeSwitches& s) {
  if (s.parallel && s.pose == PoseStorage::SharedScratch)
    return "a shared scratch pose (the BGE's bPose swap) cannot be filled by several threads: use --pose per-copy";
  return {};
}

std::string_view to_string(Lookups lookups) {
  return lookups == Lookups::PerFrameString ? "string" : "bundled";
}
std::string_view to_string(PoseStorage pose) { return pose == PoseStorage::SharedScratch ? "shared" : "per-copy"; }
std::string_view to_string(SkinningSite site) {
  switch (site) {
    case SkinningSite::CpuInRasterizer: return "rasterizer";
    case SkinningSite::CpuInAnimations: return "animations";
    case SkinningSite::Gpu: return "gpu";
  }
  return "?";
}

std::string_view to_string(VertexFormat format) { return format == VertexFormat::Packed ? "packed" : "float"; }

}  // namespace crowdprof

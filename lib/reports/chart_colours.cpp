#include "reports/chart_colours.h"

#include <algorithm>
#include <array>

#include "base/modes.h"

namespace crowdprof {

namespace {

// Okabe-Ito: told apart with every common colour-vision deficiency. The first
// four are the four presets (master, culled, threaded, hwskin).
constexpr std::array<const char*, 8> kModeColours = {"#D55E00", "#E69F00", "#0072B2", "#009E73",
                                                     "#CC79A7", "#56B4E9", "#000000", "#F0E442"};
// Tableau 10, in the BGE's category order: Animations and Rasterizer, the two
// that carry most frames, get the two most distinct hues.
constexpr std::array<const char*, kCategoryCount> kCategoryColours = {
    "#9C755F",  // Physics
    "#B07AA1",  // Logic
    "#4E79A7",  // Animations
    "#BAB0AC",  // Network
    "#59A14F",  // Scenegraph
    "#F28E2B",  // Rasterizer
    "#76B7B2",  // Services
    "#EDC948",  // Overhead
    "#FF9DA7",  // Outside
    "#E15759",  // GPU Latency
};

}  // namespace

const char* category_colour(Category category) {
  return kCategoryColours[static_cast<size_t>(category)];
}

ModeColours::ModeColours() {
  for (const ModePreset& preset : mode_presets()) fixed_.emplace_back(preset.name);
}

const char* ModeColours::colour(std::string_view name) {
  auto fixed = std::find(fixed_.begin(), fixed_.end(), name);
  if (fixed != fixed_.end()) return kModeColours[static_cast<size_t>(fixed - fixed_.begin()) % kModeColours.size()];
  auto other = std::find(others_.begin(), others_.end(), name);
  if (other == others_.end()) other = others_.insert(others_.end(), std::string(name));
  // Spare colours follow the fixed ones, so a custom mode never looks like a preset
  // until the palette wraps.
  size_t index = fixed_.size() + static_cast<size_t>(other - others_.begin());
  return kModeColours[index % kModeColours.size()];
}

}  // namespace crowdprof

#include "reports/chart_colours.h"

#include <algorithm>
#include <array>

#include "base/modes.h"

namespace crowdprof {

namespace {

// Okabe-Ito: told apart with every common colour-vision deficiency. The first
// four are the four presets (master, culled, threaded, hwskin). Its light
// colours (orange, sky blue, yellow) are darkened, or a purple takes the sky
// blue's place, so that every colour has 3:1 or more against the white page
// (WCAG 2.1 for graphics; the page's self-check holds charts to it).
constexpr std::array<const char*, 8> kModeColours = {"#D55E00", "#A66A00", "#0072B2", "#009E73",
                                                     "#B8568F", "#6A3D9A", "#000000", "#8C7A00"};
// Tableau 10, in the BGE's category order: Animations and Rasterizer, the two
// that carry most frames, get the two most distinct hues. Its light colours
// darkened to 3:1 or more against white, their hues kept.
constexpr std::array<const char*, kCategoryCount> kCategoryColours = {
    "#9C755F",  // Physics (4.1:1 against white)
    "#B07AA1",  // Logic (3.4:1)
    "#4E79A7",  // Animations (4.6:1)
    "#7F7F7F",  // Network (4.0:1)
    "#59A14F",  // Scenegraph (3.2:1)
    "#C9650A",  // Rasterizer (3.9:1)
    "#2F8F89",  // Services (3.9:1)
    "#9E8200",  // Overhead (3.7:1)
    "#C4587E",  // Outside (4.2:1)
    "#E15759",  // GPU Latency (3.7:1)
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

// One colour per category and per mode in every chart crowdprof draws (the SVG
// files and the HTML report), so a reader who learnt that Animations is blue
// and master is orange in one chart reads every other chart the same way.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "profile/category_clock.h"

namespace crowdprof {

// The category's colour, fixed by the category (not by its place among the
// categories a chart shows).
const char* category_colour(Category category);

// Colours of the modes (or other series: "baseline", a file name) of one
// document. A name in `fixed` takes the colour of its place there: callers pass
// the presets in their order (base/modes.h preset_mode_names()), so a preset has
// the same colour in every chart and every report. Any other name takes the
// next spare colour, in the order asked, and keeps it.
class ModeColours {
 public:
  explicit ModeColours(std::vector<std::string> fixed = {}) : fixed_(std::move(fixed)) {}
  const char* colour(std::string_view name);

 private:
  std::vector<std::string> fixed_, others_;
};

}  // namespace crowdprof

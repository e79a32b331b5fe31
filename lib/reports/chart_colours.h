// One colour per category and per mode in every chart crowdprof draws (the SVG
// files and the HTML report), so a reader who learnt that Animations is blue
// and master is orange in one chart reads every other chart the same way.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "measuring/category_clock.h"

namespace crowdprof {

// The category's colour, fixed by the category (not by its place among the
// categories a chart shows).
const char* category_colour(Category category);

// Colours of the modes (or other series: "baseline", a file name) of one
// document. A preset takes the colour of its place among the presets
// (base/modes.h mode_presets()), so it has the same colour in every chart and
// every report. Any other name takes the next spare colour, in the order asked,
// and keeps it.
class ModeColours {
 public:
  ModeColours();
  const char* colour(std::string_view name);

 private:
  std::vector<std::string> fixed_, others_;
};

}  // namespace crowdprof

// Each saving's price beside what it saves (issue 29 item 2): one point per
// mode of a comparison, its median frame time against the error its frames
// are drawn with (DrawnErrorRecord), the milliseconds it saves against the
// same mode without it, and whether it is on the Pareto front (no other point
// both as fast and as exact, and better in one).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "result/result.h"

namespace crowdprof {

struct CostErrorInput {
  std::string mode;                        // as the comparison names it: "threaded+update_lod=on"
  double frame_ms = 0, animations_ms = 0;  // medians
  std::optional<DrawnErrorRecord> error;
  size_t copies = 0;  // the crowd: points compare only with points of the same (0: all the same)
};

// The error a saving may cost and still be offered on the front: a pixel,
// under which a viewer cannot see it. A faster point drawn further off is
// marked past it instead (a budget that bends a pose by 15% of the height is
// fast, not a bargain).
inline constexpr double kFrontMaxErrorPx = kVisibleErrorPx;

struct CostErrorPoint {
  std::string mode, base;  // base: the point its saving is measured against; "" for none of its crowd
  double frame_ms = 0, animations_ms = 0;
  double saved_ms = 0;  // base's frame_ms - this one's (negative: it costs time)
  DrawnErrorRecord error;
  // Past kFrontMaxErrorPx on screen (error.max_px).
  bool past_threshold = false;
  // On the Pareto front and within the threshold.
  bool front = false;
  size_t copies = 0;
};

// The points of the inputs that carry an error; empty when fewer than two do.
// A mode's base is the mode named by its name up to the first '+' when the
// comparison has it ("threaded" for "threaded+mesh_lod=on"), else the first
// mode ("baked" against "instanced" in --modes instanced,baked): compare interleaves them in blocks, so the saving is
// measured side by side. The front is over frame_ms and the largest error on screen (error.max_px): savings aimed at
// far copies stray furthest in millimetres where they are smallest on screen, so pixels are what a viewer weighs. A
// point past kFrontMaxErrorPx is never on the front: it is marked past it.
std::vector<CostErrorPoint> cost_error_points(const std::vector<CostErrorInput>& inputs);

// The points as a table under compare's, with a line that says how to read it:
// front "*", or "past 1 px"; a negative saved_ms says "(slower)".
std::string format_cost_error(const std::vector<CostErrorPoint>& points);

}  // namespace crowdprof

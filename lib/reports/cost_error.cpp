#include "reports/cost_error.h"

#include <algorithm>

#include "base/number_text.h"
#include "reports/text_table.h"

namespace crowdprof {

std::vector<CostErrorPoint> cost_error_points(const std::vector<CostErrorInput>& inputs) {
  std::vector<CostErrorPoint> points;
  for (const CostErrorInput& in : inputs)
    if (in.error)
      points.push_back(CostErrorPoint{in.mode,
                                      {},
                                      in.frame_ms,
                                      in.animations_ms,
                                      0,
                                      *in.error,
                                      in.error->max_px > kFrontMaxErrorPx,
                                      false,
                                      in.copies});
  if (points.size() < 2) return {};
  // Times compare only within one crowd (capacity's modes each ran its own).
  for (CostErrorPoint& p : points) {
    const size_t plus = p.mode.find('+');
    const CostErrorPoint* base = nullptr;
    for (const CostErrorPoint& q : points)
      if (q.copies == p.copies && !base) base = &q;  // the first of its crowd
    for (const CostErrorPoint& q : points)
      if (plus != std::string::npos && q.mode == p.mode.substr(0, plus) && q.copies == p.copies) base = &q;
    if (base == &p && std::count_if(points.begin(), points.end(),
                                    [&](const CostErrorPoint& q) { return q.copies == p.copies; }) == 1) {
      p.base.clear();  // alone in its crowd: nothing to save against
      continue;
    }
    p.base = base->mode;
    p.saved_ms = base->frame_ms - p.frame_ms;
  }
  for (CostErrorPoint& p : points) {
    p.front = !p.past_threshold;
    for (const CostErrorPoint& q : points) {
      if (q.copies != p.copies) continue;
      const bool as_good = q.frame_ms <= p.frame_ms && q.error.max_px <= p.error.max_px;
      const bool better = q.frame_ms < p.frame_ms || q.error.max_px < p.error.max_px;
      if (as_good && better) p.front = false;
    }
  }
  return points;
}

std::string format_cost_error(const std::vector<CostErrorPoint>& points) {
  if (points.empty()) return {};
  std::vector<std::vector<std::string>> rows;
  rows.push_back({"mode", "frame_ms", "saved_ms", "against", "animations_ms", "max_mm", "rms_mm", "max_%height",
                  "max_px", "rms_px", "switches/s", "front"});
  for (const CostErrorPoint& p : points) {
    const DrawnErrorRecord& e = p.error;
    const std::string saved = fixed(p.saved_ms, 3) + (p.saved_ms < 0 ? " (slower)" : "");
    const bool none = p.mode == p.base || p.base.empty();
    rows.push_back({p.mode, fixed(p.frame_ms, 3), none ? "-" : saved,
                    p.base.empty() ? "- (crowd of its own)"
                    : none         ? "-"
                                   : p.base,
                    fixed(p.animations_ms, 3), fixed(e.max * 1000.0, 2), fixed(e.rms * 1000.0, 2),
                    fixed(e.max_fraction * 100.0, 3), fixed(e.max_px, 2), fixed(e.rms_px, 2),
                    fixed(e.switches_per_second, 1),
                    p.past_threshold ? "past " + fixed(kFrontMaxErrorPx, 0) + " px"
                    : p.front        ? "*"
                                     : ""});
  }
  return "\nerror beside cost: the last frame's copies on screen as drawn against their exact, full-detail pose "
         "(mm: model units x 1000); saved_ms against the mode named before '+', or the first (negative: slower "
         "than it); front: no other mode as fast and as exact on screen (max_px), among those within " +
         fixed(kFrontMaxErrorPx, 0) + " px; past " + fixed(kFrontMaxErrorPx, 0) +
         " px: drawn visibly off its exact pose, never on the front\n" + align_columns(rows, {0, 3});
}

}  // namespace crowdprof

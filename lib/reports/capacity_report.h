// How `crowdprof capacity` reports its search: a table (per mode the largest
// crowd that fits the budget and the first that did not), JSON with every
// point tried, and an SVG chart of the metric against the crowd size with the
// budget line (docs/formats.md, docs/capacity.md).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frame/capacity.h"

namespace crowdprof {

// The table for stdout: a header with units, one row per mode, then lines on
// the search (the rule, frames per point) and on each mode the result cannot
// be read from alone (capped, nothing fits, not monotonic).
std::string format_capacity(const CapacityRun& run);

// {"crowdprof": {..., "kind": "capacity"}, "environment", "scene", "budget_ms",
//  "metric", "search", "block_frames", "frames_per_point", "warmup_frames",
//  "partial", "modes": [{"mode", "threads", "cap", "largest_fit", "first_over",
//  "capped", "non_monotonic", "points": [...]}], "sweep": [{"mode",
//  "characters", "frame_median_ms"} per point, as compare's], "runs": [the bench
//  result at each mode's largest fit, else at its first size over]}: `report`
//  reads it as it reads a comparison. result_document_to_json(capacity_document(run)).
nlohmann::json capacity_to_json(const CapacityRun& run);
// The search as a typed document (kind "capacity"), which the codec writes.
ResultDocument capacity_document(const CapacityRun& run);

// The metric's median against the crowd size (log scale), one line per mode
// (the presets keep their colours, chart_colours.h), and the budget.
std::string capacity_svg(const CapacityRun& run);

}  // namespace crowdprof

// How `crowdprof compare` reports modes run side by side: a table (per mode
// the median frame, each category that took time, the speedup over the first
// mode), the same as CSV and JSON, and SVG charts (docs/formats.md).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/profile_table.h"
#include "result/result_document.h"
#include "result/sweep_axis.h"

namespace crowdprof {

struct Comparison {
  std::vector<Result> runs;                      // one per mode at the chosen crowd size, in the order asked
  std::vector<Result> sweep;                     // every (point, mode) of --sweep, by point then mode; empty without
  SweepAxis sweep_axis = SweepAxis::Characters;  // what the sweep's points vary
  size_t block = 10;                             // frames per block of the interleaving
};

// Per run (result/result_document.h's ModeMedians), with speedups against the
// first run of the same size.
std::vector<ModeMedians> mode_medians(const std::vector<Result>& runs);

// Whether `run` of the sweep is at the main runs' point (their size, or their
// passes): the same run, written once.
bool is_main_point(const Comparison& comparison, const Result& run);

// Categories to show: those whose median is at least 0.005 ms (0.00 when
// printed) in some run.
std::vector<Category> shown_categories(const std::vector<ModeMedians>& medians);

// The categories the table for stdout shows: the same columns whatever the
// values, so that two compares (two characters, two machines) line up and
// none drops a column for a median that happened to print as 0.00. Those a
// frame charges work to (Logic, Animations, Scenegraph, Rasterizer, Overhead,
// Outside), and GPU Latency when a run drew with a GL backend; never Physics,
// Network and Services, which hold no work in a crowd benchmark.
std::vector<Category> table_categories(const std::vector<Result>& runs);

// The table for stdout: a header with units, one row per mode, then (with a
// sweep) one row per size and mode.
std::string format_comparison(const Comparison& comparison);

// bench's CSV (one row per frame) for every run, the main runs first: one header.
void write_comparison_csv(const Comparison& comparison, std::ostream& out);

// The comparison as a typed document (kind "compare"): its runs, a summary row
// per run and a row per point of the sweep.
ResultDocument comparison_document(const Comparison& comparison);
// result_document_to_json(comparison_document(comparison)): {"crowdprof":
// {..., "kind": "compare"}, "environment", "block_frames", "modes", "summary":
// [per mode], "sweep": [per size and mode], "runs": [bench JSON per mode]}.
nlohmann::json comparison_to_json(const Comparison& comparison);

// Frame time per frame, one line per mode (the thesis's figure 11); a stacked
// bar of the categories per mode; with a sweep, median frame time against
// characters (log scale), one line per mode. The presets keep
// their colours (chart_colours.h).
std::string comparison_svg(const Comparison& comparison);

}  // namespace crowdprof

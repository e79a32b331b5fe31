// The charts of the HTML report, drawn from result documents (bench --json,
// the runs of compare --json) so the report shows what the files hold. Every
// chart colours categories and modes by chart_colours.h, numbers frames from
// the first measured one, and names the character and backend in its title.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "reports/chart_colours.h"
#include "gate/regression.h"
#include "result/result.h"
#include "reports/cost_error.h"
#include "reports/svg_chart.h"
#include "result/result_document.h"
#include "result/sweep_axis.h"

namespace crowdprof {

// One bench result and how the report names it: its mode,
// or more when two results share a mode.
struct ReportRun {
  std::string label;
  Result result;
  std::string source;  // the file it came from ("" when made in this process)
};

// Frame budgets drawn on frame-time charts: 60 and 30 frames a second.
inline constexpr double kBudgetsMs[] = {1000.0 / 60.0, 1000.0 / 30.0};

// A run's median frame time as every report says it: the frame at the lower
// middle of the sorted frame times, the one whose categories the BGE table
// shows (report.h's median_frame), so that a page has one median per run.
double median_frame_ms(const std::vector<double>& frame_ms);

// `value` with `decimals` decimals, as the report's tables and labels print it.
std::string report_number(double value, int decimals);

// The samples of one metric ("frame_ms", "animations_ms") of a result.
std::vector<double> result_samples(const Result& result, const std::string& key);

// The file a run was of, without its folder: the scene file ("thesis.json"),
// else the character's ("Fox.glb"); the character's name when neither is known.
std::string scene_file_name(const Result& result);

// "thesis.json × 160, backend none": what every title names (the file, not the
// character's root node, which is "Armature" in every Blender export).
std::string scene_caption(const Result& result);

// Frame time per frame, a line per run, the budgets and each run's p50, p95
// and p99 as dashed lines.
LineChart frame_time_chart(const std::vector<ReportRun>& runs, ModeColours& colours);

// One run's categories stacked per frame: a layer per category that took any
// time in any frame.
StackedArea categories_chart(const ReportRun& run);

// Median time per category, a bar per run (categories of at least 0.005 ms).
StackedBars modes_chart(const std::vector<ReportRun>& runs);

// Median frame time against crowd size on a log axis, a line per mode; with a
// budget (capacity's), the budget as a line.
LineChart sweep_chart(const std::vector<SweepPoint>& points, SweepAxis axis, const std::string& caption,
                      ModeColours& colours, std::optional<double> budget_ms = std::nullopt);

// Each run's median frame time against its largest drawn error (px), a dot
// per run and the Pareto front as a line (reports/cost_error.h); nullopt when
// fewer than two runs carry a drawn error.
std::optional<LineChart> cost_error_chart(const std::vector<CostErrorPoint>& points, ModeColours& colours);

// An advise search's every measured configuration, its metric's median (ms,
// up) against its largest drawn error (px, across): a dot per lever tried
// (a series per lever family), the path taken from the start through each
// step's lever as a line, and the budget as a horizontal line; nullopt when
// the search measured nothing.
std::optional<LineChart> advice_chart(const AdviceRecord& advice);

// The runs' points of cost against error (reports/cost_error.h): empty when
// fewer than two runs carry a drawn error.
std::vector<CostErrorPoint> run_costs(const std::vector<ReportRun>& runs);

// check's verdict per metric against the tolerance band.
VerdictChart verdict_chart(const CheckResult& result, const CheckOptions& options);

}  // namespace crowdprof

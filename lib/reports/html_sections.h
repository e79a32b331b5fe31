// The sections of the HTML report (html_report.h), each a piece of HTML:
// those that describe runs (html_run_sections.cpp) and those that give a
// verdict or a capacity (html_verdict_sections.cpp) or advice
// (html_advise_sections.cpp). html_report() puts
// them in order: the answer first.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "reports/cost_error.h"
#include "reports/html_report.h"
#include "reports/svg_chart.h"

namespace crowdprof {

// Text as HTML shows it (&, <, >, quotes escaped).
inline std::string html_text(const std::string& text) {
  return xml_escape(text);
}

inline std::string path_file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

// Labels of runs the caller did not name: the mode; with the crowd size when
// a mode comes at several sizes; with the file when even that is not enough to
// tell two results apart.
void label_runs(std::vector<ReportRun>& all);

// The headline a reader looks for first: per run the median frame, p95, p99
// and fps, to 3 significant digits, in µs below 1 ms.
std::string headline_section(const std::vector<ReportRun>& runs);
// Per run the frame's percentiles and the budgets they pass.
std::string percentile_table(const std::vector<ReportRun>& runs);
// Several runs side by side: their frames and speedups.
std::string modes_table(const std::vector<ReportRun>& runs);
// The BGE's table per run: by category, side by side or a row per run.
std::string profile_section(const std::vector<ReportRun>& runs);
// Each run's GPU time by pass (medians, and their sum against the frame's GPU
// time) with the pipeline statistics where the GL had them: only when some
// run split its GPU time.
std::string gpu_passes_section(const std::vector<ReportRun>& runs);
// Each run's Animations by stage (thread ms, medians): only when some run has
// the split (results before it have none).
std::string animation_stages_section(const std::vector<ReportRun>& runs);
// Every counter the runs recorded, in the counters' own order: those some run
// counted above zero in a table, those at zero in every run folded away under
// a line that says how many.
std::string counters_section(const std::vector<ReportRun>& runs);
// What each run was measured on.
std::string environment_section(const std::vector<ReportRun>& runs);

// The lead of a capacity page: per mode, the largest crowd within the budget.
std::string capacity_section(const CapacityRecord& c);
// The lead of an advise page (html_advise_sections.cpp): met or not and why,
// the start's and the final configuration's options and capacities, then a
// table per step of every lever measured, the one taken highlighted.
std::string advise_section(const AdviceRecord& a);
// The A/B's verdict, the page's first section: a row per metric that says
// passed or FAILED, its change with its interval against the tolerance, then
// the work and how the builds took turns.
std::string gate_section(const GateSection& gate);
// Each saving's price as a table (the scatter plot comes later): the same
// points as the cost-against-error chart, empty when it has none.
std::string cost_error_table(const std::vector<CostErrorPoint>& points);
// A stored-baseline check's verdict and its chart (a letter added to `charts`).
std::string check_section(const CheckSection& check, const std::vector<ReportRun>& runs, std::string& charts);

}  // namespace crowdprof

// The HTML report: one self-contained page (inline SVG charts, inline CSS and
// a small inline script, no network, no external font) that a person opens
// from a CI artifact store or an e-mail. It opens with its answer: check's
// verdict per metric, capacity's capacities, advise's plan with its path on
// the cost-against-error chart, the headline, and for several runs
// the speedups and each saving's cost beside its error, as tables; then frame
// time per frame with the 16.7 and 33.3 ms budgets and p50/p95/p99, the BGE
// table, the categories stacked per frame, the modes side by side and the sweep,
// the counters (those at zero folded away), the environment and the screenshot
// (docs/report.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gate/regression.h"
#include "result/result_document.h"
#include "reports/report_charts.h"
#include "reports/verdict_report.h"

namespace crowdprof {

struct CheckSection {
  CheckResult result;
  CheckOptions options;
  std::string baseline;           // the baseline's path, as given
  std::string command = "check";  // what judged: "check", or "diff" (A as the baseline)
};

// An A/B of two builds (check --against): its verdict per metric leads the page.
struct GateSection {
  GateTable table;
  double tolerance = 0;      // the slowdown a metric may show
  double confidence = 0.95;  // of the change's interval
  std::string base;          // the base build's binary, as given
};

struct HtmlReportInput {
  std::vector<std::string> sources;  // files the report was made from, named under the title
  std::vector<ReportRun> runs;       // bench results, in order; html_report labels those without
  std::vector<SweepPoint> sweep;     // compare --sweep; empty: from the runs when they span crowd sizes
  SweepAxis sweep_axis = SweepAxis::Characters;
  std::optional<double> sweep_budget_ms;  // capacity's budget on the frame, drawn on the sweep chart
  std::optional<CheckSection> check;
  std::optional<GateSection> gate;
  std::optional<CapacityRecord> capacity;
  std::optional<AdviceRecord> advice;  // advise: its plan leads, the runs are "start" and "final"
  std::string command;                 // what made the page ("diff"), named in its title when no check or capacity is
  std::string screenshot_png;          // PNG bytes; empty when no screenshot was taken
};

// Adds the document read from `path` (read_result_document): a bench result,
// a comparison's runs and sweep, a capacity search, or an advise search (its
// runs labelled "start" and "final"). InputError naming the
// file when it is not crowdprof's, truncated, of another format or incomplete.
void add_result_file(HtmlReportInput& input, const std::string& path);

// The same for a document already read (`source` names it on the page).
void add_document(HtmlReportInput& input, ResultDocument document, const std::string& source);

// A bench result already read (or made in this process).
void add_result(HtmlReportInput& input, Result result, const std::string& source);

// InputError naming `path` unless `bytes` are a PNG (its signature and IHDR).
void require_png(const std::string& bytes, const std::string& path);

// The page. Each chart is an inline <svg> (svg_chart.h's data attributes); the
// script at the end counts what the browser drew of each chart and writes
// "ok N charts" or what differs into <body data-report-check>, and any script
// error into <html data-js-errors>.
std::string html_report(const HtmlReportInput& input);

// Writes the report to `path` (UsageError naming it when it cannot).
void write_html_report(const std::string& path, const HtmlReportInput& input);

// The bytes of a PNG to show in a report; InputError naming `path` when it is
// missing or not a PNG.
std::string read_png(const std::string& path);

}  // namespace crowdprof

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "base/number_text.h"
#include "base/switch_table.h"
#include "measuring/stats.h"
#include "reports/html_sections.h"
#include "reports/profile_table.h"
#include "reports/svg_chart.h"

namespace crowdprof {

namespace {

// A p-value as the text reports print it: below 1e-4 in scientific notation,
// never "0.0000", which reads as impossible.
std::string html_p_text(double p) {
  char text[32];
  std::snprintf(text, sizeof text, p < 1e-4 ? "%.1e" : "%.4f", p);
  return text;
}

std::string signed_percent(double fraction, int decimals) {
  return std::isfinite(fraction) ? (fraction >= 0 ? "+" : "") + report_number(fraction * 100, decimals) + "%" : "n/a";
}

// Why a calibrated verdict and the raw frame times beside it disagree: the
// calibration removes the machine's speed, the raw times keep it. Empty when
// no metric is calibrated or the page does not hold both runs.
std::string calibration_note(const CheckResult& r, const std::vector<ReportRun>& runs, bool diff) {
  if (runs.size() != 2 ||
      std::none_of(r.metrics.begin(), r.metrics.end(), [](const MetricCheck& m) { return m.value_unit == "probes"; }))
    return {};
  const double base = median_frame_ms(runs[0].result.samples.frame_ms);
  const double current = median_frame_ms(runs[1].result.samples.frame_ms);
  return "<p class=\"calibration\">The verdict compares <b>calibrated</b> frames, in <b>probes</b>: each frame's time "
         "over the time of a fixed probe workload timed right after it. A machine that is faster or slower as a whole "
         "at the moment of a run (other load, its clock, another machine) moves frame and probe alike, so the ratio "
         "keeps the code's change and drops the machine's. The raw frame times on this page are not calibrated: "
         "median " +
         duration_text(base) + (diff ? " in A, " : " in the baseline, ") + duration_text(current) +
         (diff ? " in B (" : " now (") + signed_percent(base > 0 ? current / base - 1 : NAN, 1) +
         "); what of that the calibrated change does not show is the machine's drift between the two runs, not "
         "the code.</p>\n";
}

}  // namespace

std::string capacity_section(const CapacityRecord& c) {
  std::string out = "<section id=\"capacity\"><h2>Capacity: the largest crowd whose median " + html_text(c.metric) +
                    " time fits " + report_number(c.budget_ms, 3) +
                    " ms</h2>\n<table><tr><th class=\"name\">mode</th>"
                    "<th>threads</th><th>capacity (characters)</th><th>its median ms</th><th>first over</th>"
                    "<th>its median ms</th></tr>\n";
  for (const CapacityRecord::Row& row : c.rows) {
    out += "<tr><td class=\"name\">" + html_text(row.mode) + "</td><td>" + std::to_string(row.threads) +
           "</td><td><b>" + (row.fit ? std::to_string(row.fit->n) : std::string("none")) + "</b></td><td>" +
           (row.fit ? report_number(row.fit->median_ms, 3) : std::string("-")) + "</td><td>" +
           (row.over ? std::to_string(row.over->n) : "over " + std::to_string(row.cap) + " (the cap fits)") +
           "</td><td>" + (row.over ? report_number(row.over->median_ms, 3) : std::string("-")) + "</td></tr>\n";
  }
  out += "</table>\n<p>Search: from " + std::to_string(c.start) +
         " characters, doubling while the median fits, then halving the gap until the first crowd over is within " +
         report_number(c.precision * 100, 1) + "% of the capacity (or 1 character); " +
         std::to_string(c.frames_per_point) + " frames per size after " + std::to_string(c.warmup) +
         " warm-up. The runs below are each mode's at its capacity.</p></section>\n";
  return out;
}

std::string gate_section(const GateSection& gate) {
  const GateTable& t = gate.table;
  std::string out = "<section id=\"verdict\"><h2>A/B against " + html_text(path_file_name(gate.base)) + ": " +
                    (t.failed() ? "<span class=\"regression\">FAILED</span>" : "<span class=\"ok\">passed</span>") +
                    "</h2>\n<table class=\"verdict\"><tr><th class=\"name\">metric</th><th class=\"name\">verdict</th>"
                    "<th>change</th><th>interval (" +
                    report_number(gate.confidence * 100, 0) +
                    "%)</th><th>tolerance</th><th>base</th><th>current</th><th>p (Holm)</th></tr>\n";
  for (const GateRow& row : t.metrics) {
    out += "<tr><td class=\"name\">" + html_text(row.metric) + "</td><td class=\"name\">" +
           (row.failed ? "<span class=\"regression\">FAILED</span>" : "<span class=\"ok\">passed</span>") + " (" +
           html_text(row.verdict) + ")</td><td class=\"key\">" + signed_percent(row.change, 1) + "</td><td>" +
           (row.has_interval ? "[" + signed_percent(row.change_low, 1) + ", " + signed_percent(row.change_high, 1) + "]"
                             : std::string("-")) +
           "</td><td>up to +" + report_number(gate.tolerance * 100, 1) + "%</td><td>" + report_number(row.base_ms, 3) +
           " " + html_text(row.unit) + "</td><td>" + report_number(row.current_ms, 3) + " " + html_text(row.unit) +
           "</td><td>" + (row.has_p ? html_p_text(row.p) : std::string("-")) + "</td></tr>\n";
    if (!row.why.empty()) out += "<tr><td></td><td class=\"name\" colspan=\"7\">" + html_text(row.why) + "</td></tr>\n";
  }
  out += "</table>\n<p>Work: " +
         std::string(!t.work_compared ? "not compared"
                     : t.work_equal   ? "the same"
                                      : "<span class=\"regression\">CHANGED</span>") +
         (t.work_detail.empty() ? std::string() : " (" + html_text(t.work_detail) + ")") +
         ". A change is current over base, of each group's paired medians; a metric fails when it is slower than the "
         "tolerance and the floor, and significantly so.</p>\n";
  if (!t.title.empty()) out += "<pre>" + html_text(t.title) + "</pre>\n";
  if (!t.reproduce.empty()) out += "<p>Reproduce: <code>" + html_text(t.reproduce) + "</code></p>\n";
  return out + "</section>\n";
}

std::string cost_error_table(const std::vector<CostErrorPoint>& points) {
  if (points.empty()) return {};
  std::string out =
      "<table class=\"cost-error\"><tr><th class=\"name\">mode</th><th>median frame ms</th><th>saved ms</th>"
      "<th class=\"name\">against</th><th>largest error px</th><th>rms error px</th><th>largest error mm</th>"
      "<th class=\"name\">front</th></tr>\n";
  for (const CostErrorPoint& p : points) {
    const bool base = p.mode == p.base || p.base.empty();
    out += "<tr><td class=\"name\">" + html_text(p.mode) + "</td><td>" + report_number(p.frame_ms, 3) + "</td><td>" +
           (base ? "-" : report_number(p.saved_ms, 3) + (p.saved_ms < 0 ? " (slower)" : "")) +
           "</td><td class=\"name\">" +
           (p.base.empty() ? std::string("- (a crowd of its own)")
            : base         ? "-"
                           : html_text(p.base)) +
           "</td><td>" + report_number(p.error.max_px, 2) + "</td><td>" + report_number(p.error.rms_px, 2) +
           "</td><td>" + report_number(p.error.max * 1000.0, 2) + "</td><td class=\"name\">" +
           (p.past_threshold ? "past " + report_number(kFrontMaxErrorPx, 0) + " px"
            : p.front        ? "on the front"
                             : "") +
           "</td></tr>\n";
  }
  return out +
         "</table><p>Error beside cost: the last frame's copies on screen as drawn against their exact pose; "
         "saved ms against the mode named before '+', or the first; the front: no other mode as fast and as "
         "exact on screen, among those within " +
         report_number(kFrontMaxErrorPx, 0) + " px.</p>\n";
}

std::string check_section(const CheckSection& check, const std::vector<ReportRun>& runs, std::string& charts) {
  const CheckResult& r = check.result;
  const bool warned = std::any_of(r.metrics.begin(), r.metrics.end(), [](const MetricCheck& m) { return m.excused; });
  std::string verdict = r.regressed() ? "<span class=\"regression\">REGRESSION</span>"
                        : warned      ? "<span class=\"warning\">ok, with a warning</span>"
                                      : "<span class=\"ok\">ok</span>";
  std::string out = "<section id=\"check\"><h2>" +
                    std::string(check.command == "diff" ? "Diff against " : "Check against ") +
                    html_text(check.baseline) + ": " + verdict + "</h2>\n";
  // A diff has two results, A and B, and its own verdict words (gate/diff.h).
  const bool diff = check.command == "diff";
  const std::string base = diff ? "A" : "the baseline", here = diff ? "in B" : "here";
  auto verdict_word = [&](const std::string& word) {
    if (!diff) return word;
    // diff's terminal says "same" for whatever does not fail and is not faster.
    if (word == "REGRESSION") return std::string("SLOWER");
    return word == "faster" || word == "not tested" ? word : std::string("same");
  };
  out += std::string("<table class=\"verdict\"><tr><th class=\"name\">metric</th><th>") +
         (diff ? "A median" : "baseline median") + "</th><th>" + (diff ? "B median" : "current median") +
         "</th><th>change</th><th>p (Mann-Whitney U, Holm)</th><th>floor</th><th class=\"name\">verdict</th></tr>\n";
  VerdictChart rows = verdict_chart(r, check.options);
  if (diff) {
    rows.title = "diff: change of each metric's median, A to B";
    rows.against = "A";
    for (VerdictRow& row : rows.rows) row.verdict = verdict_word(row.verdict);
  }
  for (size_t m = 0; m < r.metrics.size(); ++m) {
    const MetricCheck& metric = r.metrics[m];
    // Milliseconds, or "probes" for the calibrated frame (a ratio).
    const std::string unit = " " + metric.value_unit;
    out += "<tr><td class=\"name\">" + html_text(metric.metric) + "</td><td>" +
           metric_value_text(metric, metric.baseline.median) + unit + "</td><td>" +
           metric_value_text(metric, metric.current.median) + unit + "</td><td>" +
           (std::isfinite(metric.change) ? (metric.change >= 0 ? "+" : "") + report_number(metric.change * 100, 1) + "%"
                                         : "n/a") +
           "</td><td>" + (metric.tested ? html_p_text(metric.p_adjusted) : "-") + "</td><td>" +
           metric_value_text(metric, metric.floor_ms) + unit + "</td><td class=\"name\">" +
           html_text(rows.rows[m].verdict) + "</td></tr>\n";
  }
  out += "</table>\n<p>Tolerance " + report_number(check.options.tolerance * 100, 1) +
         "% and the floor (a slowdown must pass both; the green band is the larger), "
         "significance level " +
         report_number(check.options.alpha, 3) + " after Holm's correction over the metrics.</p>\n" +
         calibration_note(r, runs, diff);
  SvgDocument svg;
  svg.add(rows);
  charts += "v";
  out += svg.inline_svg();
  if (r.witness)
    out += "<p" + std::string(warned ? " class=\"warning\"" : "") + ">" + html_text(r.witness->line()) +
           (warned ? ". A stored baseline cannot tell this from a slower build: time the change against its base "
                     "build with <code>check --against</code>."
                   : ".") +
           "</p>\n";
  out += "<p>";
  const bool digests_equal = r.baseline_digest == r.current_digest;
  if (r.counters.empty() && r.counters_missing.empty() && digests_equal)
    out += "Counters and digest match " + base + ".";
  else if (r.counters.empty() && r.counters_missing.empty() && !r.digest_differs())
    out += "Counters match " + base + "; digest " + html_text(r.digest_note()) + ".";
  for (const CounterDifference& d : r.counters)
    out += "<span class=\"regression\">Counter " + html_text(d.name) + " changed: " + std::to_string(d.baseline) +
           " &#8594; " + std::to_string(d.current) + " per frame.</span><br>";
  for (const std::string& name : r.counters_missing)
    out += "<span class=\"regression\">Counter " + html_text(name) + " is in " + base + ", missing " + here +
           ".</span><br>";
  if (r.digest_differs())
    out += "<span class=\"regression\">Digest changed: " + html_text(r.baseline_digest) + " &#8594; " +
           html_text(r.current_digest) + "</span>";
  else if (r.digest_not_comparable() && !(r.counters.empty() && r.counters_missing.empty()))
    out += "Digest " + html_text(r.digest_note()) + ".";
  return out + "</p></section>\n";
}

}  // namespace crowdprof

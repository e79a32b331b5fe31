#include "reports/check_report.h"

#include <iomanip>
#include <sstream>

#include "base/errors.h"
#include "base/number_text.h"
#include "base/output_file.h"
#include "frame/interrupt.h"
#include "measuring/stats.h"
#include "reports/html_report.h"
#include "reports/profile_table.h"
#include "reports/report_charts.h"
#include "reports/svg_chart.h"
#include "reports/verdict_report.h"
#include "result/result_codec.h"

namespace crowdprof {

namespace {

void write_check_svg(const std::string& path, const Result& baseline, const Result& current,
                     const std::string& metric) {
  std::string shown = metric == "frame_ms" ? "frame" : metric == "cpu_ms" ? "CPU" : metric;
  const bool ratio = metric == "calibrated";  // each frame over its probe: no unit
  LineChart chart{
      "check: " + shown + (ratio ? " frame" : " time") + " per frame, baseline and current: " + scene_caption(current),
      "frame (0 = the first measured, after " + std::to_string(current.run.warmup) + " warm-up)",
      ratio ? "frame over the calibration probe" : "time (ms)",
      {},
      false};
  ModeColours colours;  // baseline and current as the HTML report colours them
  for (const auto& [name, result] :
       {std::pair<const char*, const Result*>{"baseline", &baseline}, {"current", &current}}) {
    LineSeries series{name, {}, result_samples(*result, metric), colours.colour(name)};
    for (size_t i = 0; i < series.y.size(); ++i) series.x.push_back(static_cast<double>(i));
    chart.series.push_back(std::move(series));
  }
  SvgDocument svg;
  svg.add(chart);
  write_text(path, "SVG", [&](std::ostream& out) { out << svg.str(); });
}

// `ran`: the run the scene is named from.
void write_verdict_files(const CheckRun& r, GateTable table, const Result& ran, double seconds) {
  table.scene = verdict_scene(ran);
  table.seconds = seconds;
  if (!r.files.path("--junit").empty())
    write_text(r.files.path("--junit"), "JUnit XML", [&](std::ostream& out) { out << verdict_junit(table); });
  if (!r.files.path("--markdown").empty())
    write_text(r.files.path("--markdown"), "Markdown", [&](std::ostream& out) { out << verdict_markdown(table); });
}

// --update-baseline: the result becomes the baseline.
int report_baseline(const CheckRun& r, const CheckOutcome& o, std::ostream& out) {
  const Result& current = o.current;
  if (!r.files.path("--json").empty()) write_result_file(r.files.path("--json"), "JSON", current);
  write_result_file(r.baseline, "baseline", current);
  if (!r.files.path("--html").empty()) {
    HtmlReportInput input;
    add_result(input, current, r.baseline);
    write_html_report(r.files.path("--html"), input);
  }
  // --junit and --markdown hold a verdict, which recording a baseline has not:
  // they are not written, and do not take stdout.
  if (r.files.without({"--junit", "--markdown"}).prints_on_stdout(r.quiet))
    out << "baseline written: " << r.baseline << " (" << current.run.mode << ", " << current.run.characters
        << " characters, frame median " << summarize(current.samples.frame_ms).median << " ms"
        << (r.result.empty() && o.plan.runs > 1 ? ", the median of " + std::to_string(o.plan.runs) + " runs by " +
                                                      metric_display_name(o.plan.gate.metrics.front())
                                                : "")
        << ", digest " << current.digest
        << (current.instructions && current.instructions->per_frame && current.instructions->frames > 0
                ? ", " + with_thousands(static_cast<uint64_t>(*current.instructions->per_frame)) +
                      " instructions per frame over " + std::to_string(current.instructions->frames) + " frames (" +
                      current.instructions->source + ")"
                : "")
        << ")\n";
  return kExitOk;
}

// --metric instructions: the count's row in place of the timed metrics.
int report_count(const CheckRun& r, const CheckOutcome& o, std::ostream& out) {
  const CountCheck& count = o.count;
  const double tolerance = o.plan.gate.tolerance;
  CheckOptions work = o.plan.gate;
  work.metrics = {"frame_ms"};
  GateTable table = check_verdict_table(o.result, work);
  GateRow row;
  row.metric = "instructions";
  row.unit = "instructions";
  row.base_ms = count.base;
  row.current_ms = count.current;
  row.change = count.change;
  row.has_p = false;
  row.verdict = count.slower ? "slower" : count.faster ? "faster" : "no change";
  row.failed = count.slower;
  if (count.slower) row.why = "more instructions per frame than the " + percent(tolerance).substr(1) + " tolerance";
  table.metrics = {row};
  table.title = "instructions per measured frame, " + count.origin + ": stored baseline " + r.baseline + ", " +
                fixed(o.wall_s, 1) + " s";
  if (!r.files.path("--json").empty()) write_result_file(r.files.path("--json"), "JSON", o.current);
  write_verdict_files(r, table, o.current, o.wall_s);
  if (r.files.prints_on_stdout(r.quiet)) {
    out << "instructions per frame: " << fixed(count.base, 0) << " -> " << fixed(count.current, 0) << " ("
        << percent(count.change) << "; tolerance " << percent(tolerance).substr(1) << "), "
        << (count.slower ? "SLOWER" : row.verdict) << "; counted by " << count.origin << "\n";
    out << "work: " << (table.work_compared ? (table.work_equal ? "the same" : "CHANGED") : "not compared") << " ("
        << table.work_detail << ")\n";
  }
  return table.failed() ? kExitRegression : kExitOk;
}

// The timed gate against a stored baseline.
int report_gate(const CheckRun& r, const CheckOutcome& o, std::ostream& out) {
  const Result& baseline = *o.baseline;
  const Result& current = o.current;
  const CheckOptions& options = o.plan.gate;
  std::string current_name = r.result.empty() ? std::string("the run") : r.result;
  if (!r.files.path("--json").empty()) write_result_file(r.files.path("--json"), "JSON", current);
  if (!r.files.path("--svg").empty())
    write_check_svg(r.files.path("--svg"), baseline, current, options.metrics.front());
  if (!r.files.path("--html").empty()) {
    // Both runs side by side under the verdict.
    HtmlReportInput input;
    add_result(input, baseline, r.baseline);
    add_result(input, current, r.result.empty() ? "this run" : r.result);
    input.runs[0].label = "baseline";
    input.runs[1].label = "current";
    input.check = CheckSection{o.result, options, r.baseline};
    write_html_report(r.files.path("--html"), input);
  }
  if (!r.files.path("--junit").empty() || !r.files.path("--markdown").empty()) {
    GateTable table = check_verdict_table(o.result, options);
    table.title = "stored baseline " + r.baseline + " against " + current_name + ", " + fixed(o.wall_s, 1) + " s";
    if (o.result.witness) table.title += "\n" + o.result.witness->line();
    write_verdict_files(r, table, current, o.wall_s);
  }
  if (r.files.prints_on_stdout(r.quiet)) out << format_check(o.result, options);
  return o.result.regressed() ? kExitRegression : kExitOk;
}

// check --against: the A/B of two builds.
int report_ab(const CheckRun& r, const AbRun& ab, std::ostream& out) {
  GateTable table = ab_verdict_table(ab.result, ab.gate);
  table.command = "crowdprof check --against";
  std::ostringstream title;
  title << "A/B: " << r.groups << " groups (ABBA/BAAB), " << 4 * r.groups << " processes, " << std::fixed
        << std::setprecision(1) << ab.wall_s << " s\n  base:    " << ab.base_version
        << "\n  current: " << ab.current_version;
  table.title = title.str();
  table.reproduce = ab.reproduce;
  if (!r.files.path("--json").empty())
    write_text(r.files.path("--json"), "JSON", [&](std::ostream& file) { file << ab.document().dump(2) << "\n"; });
  write_verdict_files(r, table, ab.last_current, ab.wall_s);
  if (!r.files.path("--html").empty()) {
    HtmlReportInput input;
    add_result(input, ab.last_base, ab.base_binary);
    add_result(input, ab.last_current, ab.current_binary);
    input.runs[0].label = "base";
    input.runs[1].label = "current";
    // The verdict leads the page, the last process of each build under it.
    input.gate = GateSection{table, ab.gate.tolerance, ab.gate.confidence, ab.base_binary};
    write_html_report(r.files.path("--html"), input);
  }
  if (r.files.prints_on_stdout(r.quiet)) out << verdict_text(table);
  return ab.result.regressed() ? kExitRegression : kExitOk;
}

}  // namespace

int report_check(const CheckRun& request, const CheckOutcome& outcome, std::ostream& out) {
  switch (outcome.kind) {
    case CheckOutcome::Kind::Interrupted:
      return kExitInterrupted;
    case CheckOutcome::Kind::BaselineWritten:
      return report_baseline(request, outcome, out);
    case CheckOutcome::Kind::Counted:
      return report_count(request, outcome, out);
    case CheckOutcome::Kind::Gated:
      return report_gate(request, outcome, out);
    case CheckOutcome::Kind::Ab:
      return report_ab(request, *outcome.ab, out);
  }
  return kExitOk;
}

int check_and_report(CheckRun request, std::ostream& out) {
  if (!request.files.path("--csv").empty())
    request.each_run = [path = request.files.path("--csv")](const Result& run) {
      write_text(path, "CSV", [&](std::ostream& file) { write_csv(run, file); });
    };
  return report_check(request, run_check(request), out);
}

}  // namespace crowdprof

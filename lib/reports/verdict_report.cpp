#include "reports/verdict_report.h"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "base/number_text.h"   // percent
#include "reports/svg_chart.h"  // xml_escape
#include "reports/text_table.h"

namespace crowdprof {

bool GateTable::failed() const {
  if (work_compared && !work_equal) return true;
  for (const GateRow& row : metrics)
    if (row.failed) return true;
  return false;
}

std::string GateTable::name() const {
  return scene.empty() ? command : command + " (" + scene + ")";
}

std::string verdict_scene(const Result& result) {
  const std::string& path = result.run.scene_file.empty() ? result.run.file : result.run.scene_file;
  std::string text = path.substr(path.find_last_of('/') + 1) + " × " + std::to_string(result.run.characters);
  if (!result.run.mode.empty()) text += ", " + result.run.mode;
  return text;
}

namespace {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

std::string ms(double value) {
  return format(value < 1 ? "%.4f" : "%.3f", value);
}
// A row's value with its unit: "1.234 ms", "22210727 instructions".
std::string value(const GateRow& row, double v) {
  if (row.unit == "ms") return ms(v) + " ms";
  return (row.unit == "probes" ? ms(v) : format("%.0f", v)) + " " + row.unit;
}

std::string interval(const GateRow& row) {
  if (!row.has_interval) return "-";
  std::string text = "[";  // appended, not a + chain: GCC 12 warns falsely (-Wrestrict) on that
  text.append(percent(row.change_low)).append(", ").append(percent(row.change_high)).append("]");
  return text;
}
std::string p_text(double p) {
  return p < 0.001 ? "<0.001" : format("%.3f", p);
}
std::string p_text(const GateRow& row) {
  return row.has_p ? p_text(row.p) : "-";
}

std::string work_digest_detail(const std::string& base, const std::string& current) {
  return base == current ? "digest " + base : "digest " + base + " -> " + current;
}

std::string counters_detail(const std::vector<CounterDifference>& counters) {
  std::string text;
  for (const CounterDifference& counter : counters)
    text += (text.empty() ? "" : ", ") + counter.name + " " + std::to_string(counter.baseline) + " -> " +
            std::to_string(counter.current);
  return text;
}

std::string markdown_cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

// An attribute's value: one line (CI systems show it as a heading), its
// lines trimmed and joined by "; " and runs of spaces made one, escaped.
std::string attribute(const std::string& text) {
  std::string line;
  std::istringstream lines(text);
  for (std::string part; std::getline(lines, part);) {
    std::string words;
    for (char c : part)
      if (!((c == ' ' || c == '\r') && (words.empty() || words.back() == ' '))) words += c == '\r' ? ' ' : c;
    while (!words.empty() && words.back() == ' ') words.pop_back();
    if (!words.empty()) line += (line.empty() ? "" : "; ") + words;
  }
  return xml_escape(line);
}

std::string failure_message(const GateRow& row) {
  return row.metric + " " + percent(row.change) + " (" + value(row, row.base_ms) + " -> " + value(row, row.current_ms) +
         (row.has_interval ? ", interval " + interval(row) : "") + ", p " + p_text(row) + "): " + row.why;
}

}  // namespace

GateTable ab_verdict_table(const AbResult& result, const AbOptions& options) {
  GateTable table;
  for (const AbMetric& metric : result.metrics) {
    GateRow row;
    row.metric = metric_display_name(metric.metric);
    row.base_ms = metric.base_ms;
    row.current_ms = metric.current_ms;
    row.change = metric.change.median;
    row.has_interval = true;
    row.change_low = metric.change.low;
    row.change_high = metric.change.high;
    row.p = metric.p_adjusted;
    row.verdict = metric.regressed ? "slower" : metric.improved ? "faster" : "no change";
    row.failed = metric.regressed;
    if (row.failed)
      row.why = "slower by more than the " + percent(options.tolerance).substr(1) + " tolerance and the " +
                ms(metric.floor_ms) + " ms floor, significant at " + format("%g", options.alpha) +
                " (Wilcoxon signed-rank over " + std::to_string(metric.ratios.size()) + " paired groups)";
    table.metrics.push_back(std::move(row));
  }
  table.work_compared = result.work.compared;
  table.work_equal = result.work.equal;
  if (result.work.compared) {
    table.work_detail = work_digest_detail(result.work.base_digest, result.work.current_digest);
    if (!result.work.digest_note.empty()) table.work_detail += " (" + result.work.digest_note + ")";
    if (!result.work.counters.empty()) table.work_detail += "; " + counters_detail(result.work.counters);
    if (!result.work.run_difference.empty()) table.work_detail += "; the runs differ: " + result.work.run_difference;
    if (!result.work.inconsistent.empty())
      table.work_detail += "; the " + result.work.inconsistent + " build's own runs did different work";
  }
  return table;
}

GateTable check_verdict_table(const CheckResult& result, const CheckOptions& options) {
  GateTable table;
  for (const MetricCheck& metric : result.metrics) {
    GateRow row;
    row.metric = metric.metric;
    row.base_ms = metric.baseline.median;
    row.current_ms = metric.current.median;
    row.change = metric.change;
    row.p = metric.p_adjusted;
    const bool faster = significantly_faster(metric, options);
    row.verdict = !metric.tested     ? "not tested"
                  : metric.regressed ? "slower"
                  : metric.excused   ? "slower, a warning"
                  : faster           ? "faster"
                                     : "no change";
    row.has_p = metric.tested;
    row.failed = metric.regressed;
    row.unit = metric.value_unit;
    if (row.failed)
      row.why = "slower by more than the " + percent(options.tolerance).substr(1) + " tolerance and the " +
                ms(metric.floor_ms) + " " + metric.value_unit + " floor, significant at " +
                format("%g", options.alpha) + " (Mann-Whitney over " + metric.unit + ")";
    if (metric.work_grew && result.witness)
      row.why = "its median slower by more than the " + percent(options.tolerance).substr(1) +
                " tolerance (runs too spread to test) and instructions per frame " + percent(result.witness->change) +
                ", beyond it too";
    if (metric.excused && result.witness)
      row.why =
          "slower beyond the tolerance with the same instructions per frame, on a machine that was not as it "
          "was for the baseline (" +
          result.witness->machine() + "): time the change with check --against";
    table.metrics.push_back(std::move(row));
  }
  table.work_compared = options.compare_work;
  table.work_equal = !result.digest_differs() && result.counters.empty() && result.counters_missing.empty();
  table.work_detail = work_digest_detail(result.baseline_digest, result.current_digest);
  if (result.digest_not_comparable()) table.work_detail += " (" + result.digest_note() + ")";
  if (!result.counters.empty()) table.work_detail += "; " + counters_detail(result.counters);
  for (const std::string& name : result.counters_missing) table.work_detail += "; no counter " + name;
  return table;
}

std::string verdict_text(const GateTable& table) {
  std::ostringstream out;
  if (!table.title.empty()) out << table.title << "\n";
  std::vector<std::vector<std::string>> rows = {
      {"metric", "base_ms", "current_ms", "change", "interval", "p", "verdict"}};
  for (const GateRow& row : table.metrics)
    rows.push_back({row.metric, ms(row.base_ms), ms(row.current_ms), percent(row.change), interval(row), p_text(row),
                    row.verdict});
  out << align_columns(rows, {0, 4, 6});
  if (table.work_compared)
    out << "work: " << (table.work_equal ? "the same" : "CHANGED") << " (" << table.work_detail << ")\n";
  else
    out << "work: not compared (--timings-only)\n";
  if (table.failed() && !table.reproduce.empty()) out << "reproduce: " << table.reproduce << "\n";
  return out.str();
}

std::string verdict_junit(const GateTable& table) {
  size_t cases = table.metrics.size() + 1, failures = 0;
  for (const GateRow& row : table.metrics) failures += row.failed;
  bool work_failed = table.work_compared && !table.work_equal;
  failures += work_failed;
  const std::string suite = attribute(table.name());
  const std::string time = " time=\"" + format("%.3f", table.seconds) + "\"";
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"crowdprof\" tests=\"" << cases << "\" failures=\"" << failures << "\"" << time << ">\n"
      << "  <testsuite name=\"" << suite << "\" tests=\"" << cases << "\" failures=\"" << failures
      << "\" errors=\"0\" skipped=\"" << (table.work_compared ? 0 : 1) << "\"" << time << ">\n";
  if (!table.scene.empty() || !table.title.empty()) {
    out << "    <properties>";
    if (!table.scene.empty()) out << "<property name=\"scene\" value=\"" << attribute(table.scene) << "\"/>";
    if (!table.title.empty()) out << "<property name=\"compared\" value=\"" << attribute(table.title) << "\"/>";
    out << "</properties>\n";
  }
  for (const GateRow& row : table.metrics) {
    out << "    <testcase classname=\"" << suite << "\" name=\"" << attribute(row.metric) << "\"" << time << ">\n";
    if (row.failed)
      out << "      <failure message=\"" << attribute(failure_message(row)) << "\" type=\"slower\">"
          << xml_escape(table.reproduce.empty() ? "" : "reproduce: " + table.reproduce) << "</failure>\n";
    out << "      <system-out>"
        << xml_escape(row.verdict + ": " + value(row, row.base_ms) + " -> " + value(row, row.current_ms) + ", " +
                      percent(row.change) + ", interval " + interval(row) + ", p " + p_text(row) +
                      (!row.failed && !row.why.empty() ? ": " + row.why : ""))
        << "</system-out>\n"
        << "    </testcase>\n";
  }
  out << "    <testcase classname=\"" << suite << "\" name=\"work\"" << time << ">\n";
  if (!table.work_compared)
    out << "      <skipped message=\"not compared (--timings-only)\"/>\n";
  else if (work_failed)
    out << "      <failure message=\"" << attribute("the work changed: " + table.work_detail) << "\" type=\"work\">"
        << xml_escape(table.work_detail) << "</failure>\n";
  else
    out << "      <system-out>" << xml_escape("the same: " + table.work_detail) << "</system-out>\n";
  out << "    </testcase>\n";
  // What was compared, its lines as lines.
  if (!table.title.empty()) out << "    <system-out>" << xml_escape(table.title) << "</system-out>\n";
  out << "  </testsuite>\n</testsuites>\n";
  return out.str();
}

std::string verdict_markdown(const GateTable& table) {
  std::ostringstream out;
  out << "### " << markdown_cell(table.name()) << ": " << (table.failed() ? "FAILED" : "passed") << "\n\n";
  // The title's lines as lines (a hard break each), not one run-on paragraph.
  if (!table.title.empty()) {
    std::istringstream lines(table.title);
    for (std::string line; std::getline(lines, line);)
      out << markdown_cell(line.substr(std::min(line.find_first_not_of(' '), line.size()))) << "  \n";
    out << "\n";
  }
  out << "| metric | base | current | change | interval | p | verdict |\n|---|---:|---:|---:|---|---:|---|\n";
  for (const GateRow& row : table.metrics)
    out << "| " << markdown_cell(row.metric) << " | " << value(row, row.base_ms) << " | " << value(row, row.current_ms)
        << " | " << percent(row.change) << " | " << interval(row) << " | " << p_text(row) << " | "
        << (row.failed ? "**" + row.verdict + "**" : row.verdict) << " |\n";
  out << "\n";
  for (const GateRow& row : table.metrics)
    if (!row.failed && !row.why.empty())
      out << "Warning, " << markdown_cell(row.metric) << ": " << markdown_cell(row.why) << ".\n\n";
  if (table.work_compared)
    out << "Work: " << (table.work_equal ? "the same" : "**changed**") << " (" << markdown_cell(table.work_detail)
        << ").\n";
  else
    out << "Work: not compared (`--timings-only`).\n";
  if (table.failed() && !table.reproduce.empty()) out << "\nReproduce:\n\n```sh\n" << table.reproduce << "\n```\n";
  return out.str();
}

}  // namespace crowdprof

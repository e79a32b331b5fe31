#include "reports/html_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <tuple>

#include "base/errors.h"
#include "base/output_file.h"
#include "base/switch_table.h"
#include "reports/html_sections.h"
#include "reports/page_files.h"
#include "reports/profile_table.h"
#include "result/result_codec.h"
#include "base/number_text.h"
#include "measuring/stats.h"

namespace crowdprof {

namespace {

std::string base64(const std::string& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = static_cast<uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 2]);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

}  // namespace

void require_png(const std::string& bytes, const std::string& path) {
  static const std::string kSignature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.size() < 33 || bytes.compare(0, 8, kSignature) != 0 || bytes.compare(12, 4, "IHDR") != 0)
    throw InputError(path, "not a PNG image");
}

void add_document(HtmlReportInput& input, ResultDocument document, const std::string& source) {
  // An advise search's runs are its start and its final configuration, whose
  // modes may well be the same.
  const bool advise = document.kind == "advise";
  // A page leads with one plan: a second would take the first one's place.
  if (advise && (input.advice || !input.runs.empty()))
    throw InputError(source, "an advise result is a page of its own: report it alone");
  if (!advise && input.advice) throw InputError(source, "after an advise result: report the advise result alone");
  for (size_t r = 0; r < document.runs.size(); ++r)
    input.runs.push_back({advise ? (r == 0   ? "start"
                                    : r == 1 ? "final"
                                             : "run " + std::to_string(r + 1))
                                 : "",
                          std::move(document.runs[r]), source});
  if (document.kind == "bench") return;
  if (advise) {
    input.advice = std::move(document.advice);
    return;
  }
  input.sweep_axis = document.sweep_axis;
  for (const ModeMedians& m : document.sweep) input.sweep.push_back({m.mode, m.on(document.sweep_axis), m.frame_ms});
  if (document.capacity && document.capacity->metric == "frame" && document.capacity->budget_ms > 0)
    input.sweep_budget_ms = document.capacity->budget_ms;
  if (document.capacity) input.capacity = std::move(document.capacity);
}

void add_result(HtmlReportInput& input, Result result, const std::string& source) {
  if (input.advice) throw InputError(source, "after an advise result: report the advise result alone");
  input.runs.push_back({"", std::move(result), source});
}

void add_result_file(HtmlReportInput& input, const std::string& path) {
  add_document(input, read_result_document(path), path);
  input.sources.push_back(path);
}

std::string html_report(const HtmlReportInput& given) {
  HtmlReportInput input = given;
  if (input.runs.empty()) throw UsageError("a report needs at least one result");
  label_runs(input.runs);
  ModeColours colours;
  for (const ReportRun& run : input.runs) colours.colour(run.label);  // in order, before any chart asks
  const Result& first = input.runs.front().result;
  std::string caption = scene_caption(first);
  // Named by the files it was made from, so that several reports open side
  // by side (tabs, a CI's artifacts) tell themselves apart.
  std::string from;
  for (size_t s = 0; s < std::min<size_t>(input.sources.size(), 2); ++s)
    from += (s ? ", " : " of ") + path_file_name(input.sources[s]);
  if (input.sources.size() > 2) from += " and " + std::to_string(input.sources.size() - 2) + " more";
  std::string title = "crowdprof report" + from + ": " + caption +
                      (input.advice ? ", advise: " + significant(input.advice->budget_ms, 3) + " ms budget on " +
                                          input.advice->metric + ": " + (input.advice->met ? "met" : "not met")
                       : input.capacity ? ", capacity within " + report_number(input.capacity->budget_ms, 3) +
                                              " ms of " + input.capacity->metric
                       : input.gate ? ", A/B check against " + path_file_name(input.gate->base) + ": " +
                                          (input.gate->table.failed() ? "FAILED" : "passed")
                       : input.check            ? ", " + input.check->command
                       : !input.command.empty() ? ", " + input.command
                       : input.runs.size() > 1  ? ", " + std::to_string(input.runs.size()) + " runs"
                                                : ", " + input.runs.front().label);
  std::string charts;  // one letter per chart, for the count the page checks
  std::string body;
  body += "<h1>" + html_text(title) + "</h1>\n<p class=\"sources\">";
  if (!input.sources.empty()) {
    body += "From ";
    for (size_t s = 0; s < input.sources.size(); ++s) body += (s ? ", " : "") + html_text(input.sources[s]);
    body += ". ";
  }
  body += "Made by crowdprof " + html_text(first.environment.version) + "; one file, no network needed.</p>\n";
  // The answer first: the verdict, the capacities, the headline and, for
  // several runs, the speedups and each saving's price; the charts after.
  if (input.gate) body += gate_section(*input.gate);
  if (input.capacity) body += capacity_section(*input.capacity);
  if (input.check) body += check_section(*input.check, input.runs, charts);
  if (input.advice) {
    body += advise_section(*input.advice);
    if (std::optional<LineChart> chart = advice_chart(*input.advice)) {
      SvgDocument svg;
      svg.add(*chart);
      charts += "a";
      body += "<section id=\"advice-path\"><h2>Cost against error, and the path taken</h2>\n" + svg.inline_svg() +
              "<p>A dot per lever measured, at its configuration's largest drawn error and its median; the line joins "
              "the start to each step's lever taken; the red line is the budget.</p></section>\n";
    }
  }
  body += headline_section(input.runs);
  const std::vector<CostErrorPoint> costs = run_costs(input.runs);
  if (input.runs.size() > 1)
    body += "<section id=\"speedups\"><h2>Modes side by side</h2>\n" + modes_table(input.runs) +
            cost_error_table(costs) + "</section>\n";

  SvgDocument frame_svg;
  frame_svg.add(frame_time_chart(input.runs, colours));
  charts += "f";
  body += "<section id=\"frame-time\"><h2>Frame time per frame</h2>\n" + frame_svg.inline_svg() +
          percentile_table(input.runs) + "</section>\n";
  body += profile_section(input.runs);
  body += gpu_passes_section(input.runs);
  body += animation_stages_section(input.runs);

  body += "<section id=\"categories\"><h2>Categories per frame</h2>\n";
  for (const ReportRun& run : input.runs) {
    SvgDocument svg;
    svg.add(categories_chart(run));
    charts += "c";
    body += svg.inline_svg();
  }
  body += "</section>\n";

  if (input.runs.size() > 1) {
    SvgDocument svg;
    svg.add(modes_chart(input.runs));
    charts += "m";
    if (std::optional<LineChart> chart = cost_error_chart(costs, colours)) {
      svg.add(*chart);
      charts += "e";
    }
    body += "<section id=\"modes\"><h2>Modes side by side, charted</h2>\n" + svg.inline_svg() + "</section>\n";
  }

  std::vector<SweepPoint> sweep = input.sweep;
  std::set<size_t> sizes;
  for (const ReportRun& run : input.runs) sizes.insert(run.result.run.characters);
  if (sweep.empty() && sizes.size() > 1)
    for (const ReportRun& run : input.runs)
      sweep.push_back({run.result.run.mode, run.result.run.characters, quantile(run.result.samples.frame_ms, 0.5)});
  if (!sweep.empty()) {
    SvgDocument svg;
    svg.add(sweep_chart(sweep, input.sweep_axis, scene_file_name(first), colours, input.sweep_budget_ms));
    charts += "s";
    body += std::string("<section id=\"sweep\"><h2>") +
            (input.sweep_axis == SweepAxis::Passes ? "Passes sweep" : "Crowd size sweep") + "</h2>\n" +
            svg.inline_svg() + "</section>\n";
  }

  body += counters_section(input.runs);
  body += environment_section(input.runs);
  if (!input.screenshot_png.empty())
    body +=
        "<section id=\"screenshot\"><h2>Screenshot (the last frame)</h2>\n<img class=\"screenshot\" alt=\"the last "
        "frame drawn\" src=\"data:image/png;base64," +
        base64(input.screenshot_png) + "\"></section>\n";

  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" "
         "content=\"width=device-width, initial-scale=1\">\n<title>" +
         html_text(title) + "</title>\n<script>\n" + std::string(page_file("lib/reports/page/error_hook.js")) +
         "</script>\n<style>\n" + std::string(page_file("lib/reports/page/report.css")) +
         "</style>\n</head>\n<body data-charts=\"" + std::to_string(charts.size()) + "\">\n" + body + "<script>\n" +
         std::string(page_file("lib/reports/page/self_check.js")) + "</script>\n</body>\n</html>\n";
}

void write_html_report(const std::string& path, const HtmlReportInput& input) {
  write_file(path, "HTML", html_report(input));
}

std::string read_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be read");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  require_png(bytes, path);
  return bytes;
}

}  // namespace crowdprof

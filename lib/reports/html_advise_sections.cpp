// The lead of an advise page (html_sections.h): the plan, then every step's
// levers as a table.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "base/number_text.h"
#include "reports/html_sections.h"

namespace crowdprof {

namespace {

// A median and its interval with as many decimals as the largest of the three
// needs for 3 significant digits (1 from 10 ms, 3 below 1 ms).
std::string advice_interval_text(const MsInterval& i) {
  const double largest = std::max({std::abs(i.median), std::abs(i.low), std::abs(i.high)});
  const int decimals = largest >= 10 ? 1 : largest >= 1 ? 2 : 3;
  return report_number(i.median, decimals) + "<br><span class=\"interval\">[" + report_number(i.low, decimals) + ", " +
         report_number(i.high, decimals) + "]</span>";
}

// Options as users type them, each option with its value kept on one line
// ("--share on" never breaks after its dashes), the text as typed.
std::string advice_options_html(const std::string& options) {
  std::string out;
  for (size_t at = 0; at < options.size();) {
    size_t next = options.find(" --", at);
    if (next == std::string::npos) next = options.size();
    // Appended piece by piece: GCC 12 warns falsely on `"" + string` (-Wrestrict, its bug 105329).
    if (!out.empty()) out += ' ';
    out += "<span class=\"option\">";
    out += html_text(options.substr(at, next - at));
    out += "</span>";
    at = next == options.size() ? next : next + 1;
  }
  return "<code>" + out + "</code>";
}

std::string measured_capacity_cells(const AdviceRecord& a, const std::string& configuration) {
  for (const AdviceCapacity& c : a.capacities)
    if (c.configuration == configuration || c.configuration == "start and final")
      return "<td><b>" + (c.fit ? with_thousands(*c.fit) : std::string("none")) + "</b></td><td>" +
             (c.over ? with_thousands(*c.over) : std::string(c.capped ? "none (the cap fits)" : "-")) + "</td><td>" +
             std::to_string(c.measured) + "</td>";
  return "<td>not measured</td><td>-</td><td>-</td>";
}

std::string plan_row(const AdviceRecord& a, const std::string& configuration, const std::string& options,
                     const AdviceCandidate* at) {
  return "<tr><td class=\"name\">" + configuration + "</td><td class=\"name\">" +
         advice_options_html(options.empty() ? "(none)" : options) + "</td><td>" +
         (at ? advice_interval_text(at->metric) : std::string("-")) + "</td><td>" +
         (at && at->error_measured ? report_number(at->error_px, 2) : std::string("-")) + "</td>" +
         measured_capacity_cells(a, configuration) + "<td>" +
         (at ? with_thousands(at->capacity_estimate) : std::string("-")) + "</td></tr>\n";
}

std::string verdict_cell(const AdviceCandidate& c) {
  if (c.verdict == "taken") return "<b>taken</b>";
  if (c.verdict == "noise") return "noise: 0 is inside the saving's interval";
  return html_text(c.verdict);
}

std::string step_table(const AdviceRecord& a, const AdviceStep& step, size_t number) {
  const AdviceCandidate& base = step.candidates.front();
  std::string out = "<h3>Step " + std::to_string(number) + ": from " + duration_text(base.metric.median) + ", " +
                    (step.taken ? "took " + html_text(step.candidates[*step.taken].lever) : std::string("took none")) +
                    "</h3>\n<table class=\"advice-step\"><tr><th class=\"name\">lever</th><th class=\"name\">"
                    "changes</th><th>" +
                    html_text(a.metric) +
                    " median ms [interval]</th><th>saved ms [interval]</th><th>error px</th><th>error mm</th>"
                    "<th>error % of height</th><th>capacity (estimated)</th><th class=\"name\">verdict</th></tr>\n";
  for (size_t c = 0; c < step.candidates.size(); ++c) {
    const AdviceCandidate& candidate = step.candidates[c];
    const bool is_base = c == 0, measured = candidate.verdict.rfind("cannot run", 0) != 0;
    const std::string row_class = step.taken && *step.taken == c ? " class=\"taken\""
                                  : candidate.verdict == "noise" ? " class=\"noise\""
                                                                 : "";
    auto cell = [&](const std::string& text) { return "<td>" + (measured ? text : std::string("-")) + "</td>"; };
    auto error_cell = [&](double value, int decimals) {
      return cell(candidate.error_measured ? report_number(value, decimals) : std::string("-"));
    };
    out += "<tr" + row_class + "><td class=\"name\">" + (is_base ? "(the step's base)" : html_text(candidate.lever)) +
           "</td><td class=\"name\">" + (is_base ? "" : advice_options_html(candidate.changes)) + "</td>" +
           cell(advice_interval_text(candidate.metric)) +
           (is_base ? "<td>-</td>" : cell(advice_interval_text(candidate.saved))) + error_cell(candidate.error_px, 2) +
           error_cell(candidate.error_mm, 2) + error_cell(candidate.error_height_pct, 3) +
           cell(with_thousands(candidate.capacity_estimate)) + "<td class=\"name\">" + verdict_cell(candidate) +
           "</td></tr>\n";
  }
  return out + "</table>\n";
}

}  // namespace

std::string advise_section(const AdviceRecord& a) {
  std::string out = "<section id=\"advise\"><h2>Advice: " + html_text(a.metric) + " within " +
                    significant(a.budget_ms, 3) + " ms at " + with_thousands(a.characters) + " characters: " +
                    (a.met ? "<span class=\"ok\">met</span>" : "<span class=\"regression\">not met</span>") +
                    "</h2>\n<p>Outcome: <b>" + html_text(a.outcome) + "</b>." +
                    (a.met || a.ran_out.empty() ? std::string() : " " + html_text(a.ran_out)) + "</p>\n";
  out += "<table class=\"advice-plan\"><tr><th class=\"name\">configuration</th><th class=\"name\">options</th><th>" +
         html_text(a.metric) +
         " median ms [interval]</th><th>error px</th><th>capacity (measured)</th><th>first crowd over</th>"
         "<th>sizes measured</th><th>capacity (estimated)</th></tr>\n" +
         plan_row(a, "start", a.start_options, &a.start) + plan_row(a, "final", a.final_options, &a.final) +
         "</table>\n<p>The final configuration adds <code>" +
         html_text(a.added_options.empty() ? "nothing" : a.added_options) + "</code> to the start (preset " +
         html_text(a.start_mode) +
         "). A capacity measured is capacity's search of the configuration at the budget: the largest crowd whose "
         "median fits; an estimated one is " +
         with_thousands(a.characters) +
         " characters scaled by the budget over the median, as if the cost grew in proportion to the crowd. " +
         std::to_string(a.configurations_measured) + " configurations measured, " +
         std::to_string(a.frames_per_configuration) + " frames each after " + std::to_string(a.warmup) +
         " warm-up, side by side in blocks of " + std::to_string(a.block_frames) + " frames; " +
         report_number(a.elapsed_s, 0) +
         " s in all. A lever is taken when its saving's interval is above 0 and "
         "its error within " +
         shortest_text(a.max_error_px) +
         " px (or no further off than the step's base); of those, one that meets the budget alone with the least "
         "error added, else one that adds none visible (under 0.01 px) by its saving, else the one saving most per "
         "pixel of error it adds.</p>\n";
  if (!a.levers.empty()) {
    out += "<p>Levers it could try: ";
    for (size_t l = 0; l < a.levers.size(); ++l) out += (l ? ", " : "") + html_text(a.levers[l]);
    out += ".</p>\n";
  }
  if (!a.left_out.empty()) {
    out += "<p>Not tried:</p>\n<ul class=\"left-out\">";
    for (const std::string& why : a.left_out) out += "<li>" + html_text(why) + "</li>";
    out += "</ul>\n";
  }
  for (size_t s = 0; s < a.steps.size(); ++s)
    if (!a.steps[s].candidates.empty()) out += step_table(a, a.steps[s], s + 1);
  return out + "</section>\n";
}

}  // namespace crowdprof

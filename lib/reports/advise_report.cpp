#include "reports/advise_report.h"

#include "base/number_text.h"
#include "reports/summary_csv.h"
#include "reports/text_table.h"

namespace crowdprof {

namespace {

std::string interval_text(const MsInterval& i) {
  return "[" + fixed(i.low, 3) + ", " + fixed(i.high, 3) + "]";
}

// The column of the metric: "frame_ms" or "animations_ms".
std::string metric_column(const AdviceRecord& a) {
  return a.metric == "frame" ? "frame_ms" : "animations_ms";
}

}  // namespace

std::string format_advice(const AdviceRecord& a, const Result* start) {
  std::string out = "advise: " + with_thousands(a.characters) + " copies";
  if (start) out += " of " + start->run.file;
  out += ", " + a.metric + " within " + shortest_text(a.budget_ms) + " ms, drawn error within " +
         shortest_text(a.max_error_px) + " px\n";
  if (start)
    out += "host: " + start->environment.cpu + " (" + std::to_string(start->environment.cores) + " cores), SIMD " +
           start->environment.simd + "\n";
  std::string levers;
  for (const std::string& lever : a.levers) levers += (levers.empty() ? "" : ", ") + lever;
  // Considered, not all measured: one with nothing to change (threads already
  // at every core, packed vertices already packed) has no row.
  out += "levers considered: " + levers + " (one with nothing to change here has no row)\n";
  for (const std::string& line : a.left_out) out += "left out: " + line + "\n";
  if (!a.start.error_measured && a.outcome != "interrupted")
    out +=
        "no copy is on screen at the scene's camera: drawn errors are not measured (-), and levers are weighed "
        "by time alone\n";
  out += "start: " + a.start_mode + (a.start_options.empty() ? "" : " " + a.start_options) + ": " +
         fixed(a.start.metric.median, 3) + " ms " + interval_text(a.start.metric) + ", " + fixed(a.start.error_px, 2) +
         " px\n";
  if (a.outcome == "interrupted")
    out += "INTERRUPTED: a partial plan: the steps below are whole; the one in progress is left out\n";

  std::vector<std::vector<std::string>> rows = {{"step", "lever", "changes", metric_column(a), "interval", "saved_ms",
                                                 "interval", "error_px", "error_mm", "error_%h", "capacity~",
                                                 "verdict"}};
  for (size_t s = 0; s < a.steps.size(); ++s)
    for (const AdviceCandidate& c : a.steps[s].candidates) {
      const bool base = c.verdict == "base", unmeasured = c.verdict.rfind("cannot run", 0) == 0;
      if (unmeasured) {
        rows.push_back({std::to_string(s + 1), c.lever, c.changes, "-", "", "-", "", "-", "-", "-", "-", c.verdict});
        continue;
      }
      rows.push_back(
          {std::to_string(s + 1), base ? "(base)" : c.lever, c.changes, fixed(c.metric.median, 3),
           interval_text(c.metric), base ? "-" : fixed(c.saved.median, 3), base ? "" : interval_text(c.saved),
           c.error_measured ? fixed(c.error_px, 2) : "-", c.error_measured ? fixed(c.error_mm, 2) : "-",
           c.error_measured ? fixed(c.error_height_pct, 3) : "-", with_thousands(c.capacity_estimate), c.verdict});
    }
  if (a.steps.size() > 0) out += "\n" + align_columns(rows, {1, 2, 4, 6, 11}) + "\n";

  const std::string where = fixed(a.final.metric.median, 3) + " ms " + interval_text(a.final.metric);
  if (a.met)
    out += "met: " + where + " within " + shortest_text(a.budget_ms) + " ms" +
           (a.steps.empty() ? " at the start"
                            : " after " + std::to_string(a.steps.size()) + " step" + (a.steps.size() == 1 ? "" : "s")) +
           ", drawn error " + fixed(a.final.error_px, 2) + " px (" + fixed(a.final.error_mm, 2) + " mm, " +
           fixed(a.final.error_height_pct, 3) + "% of height)\n";
  else
    out += "NOT MET: " + where + " over " + shortest_text(a.budget_ms) + " ms" +
           (a.ran_out.empty() ? "" : ": " + a.ran_out) + "\n";
  out += "final: " + a.start_mode + (a.final_options.empty() ? "" : " " + a.final_options) +
         (a.added_options.empty() ? " (no lever taken)" : "") + "\n";
  if (!a.capacities.empty()) {
    out += "capacity at " + shortest_text(a.budget_ms) + " ms (capacity's search):";
    for (const AdviceCapacity& c : a.capacities) {
      out += " " + c.configuration + " " + (c.capped ? "at least " : "") +
             (c.fit ? with_thousands(*c.fit) : std::string("0")) + " copies" +
             (c.capped ? " (the largest tried: 64 times the crowd, or what memory holds)" : "") + ";";
    }
    out.back() = '\n';
    out += "capacity~: estimated, copies x budget / median\n";
  }
  out += "measured " + std::to_string(a.configurations_measured) + " configuration" +
         (a.configurations_measured == 1 ? "" : "s") + " of " + std::to_string(a.frames_per_configuration) +
         " frames (after " + std::to_string(a.warmup) + " warm-up, interleaved in blocks of " +
         std::to_string(a.block_frames) + ") in " + fixed(a.elapsed_s, 0) + " s\n";
  return out;
}

void write_advice_csv(const AdviceRecord& a, std::ostream& out) {
  out << "step,lever,changes,verdict,metric,metric_median_ms,metric_low_ms,metric_high_ms,frame_median_ms,"
         "saved_median_ms,saved_low_ms,saved_high_ms,error_px,error_mm,error_height_pct,capacity_estimate,digest\n";
  for (size_t s = 0; s < a.steps.size(); ++s)
    for (const AdviceCandidate& c : a.steps[s].candidates) {
      // Empty where nothing was measured: a lever that could not run, the
      // base's saving, an error with no copy on screen.
      const bool ran = c.verdict.rfind("cannot run", 0) != 0, paired = ran && c.verdict != "base",
                 drawn = ran && c.error_measured;
      auto cell = [](bool known, double value) { return known ? shortest_text(value) : std::string(); };
      out << s + 1 << "," << csv_field(c.lever) << "," << csv_field(c.changes) << "," << csv_field(c.verdict) << ","
          << a.metric << "," << cell(ran, c.metric.median) << "," << cell(ran, c.metric.low) << ","
          << cell(ran, c.metric.high) << "," << cell(ran, c.frame_ms) << "," << cell(paired, c.saved.median) << ","
          << cell(paired, c.saved.low) << "," << cell(paired, c.saved.high) << "," << cell(drawn, c.error_px) << ","
          << cell(drawn, c.error_mm) << "," << cell(drawn, c.error_height_pct) << ","
          << (ran ? std::to_string(c.capacity_estimate) : std::string()) << "," << c.digest << "\n";
    }
}

}  // namespace crowdprof

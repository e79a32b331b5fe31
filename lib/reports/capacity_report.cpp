#include "reports/capacity_report.h"

#include <algorithm>

#include "reports/chart_colours.h"
#include "reports/report_charts.h"
#include "base/number_text.h"
#include "reports/text_table.h"
#include "reports/svg_chart.h"
#include "result/result_codec.h"

namespace crowdprof {

namespace {

// "frame", or the category's CSV column: the table's column names.
std::string metric_column(const CapacityMetric& metric) {
  return metric.category ? std::string(category_column(*metric.category)) : "frame";
}

}  // namespace

std::string format_capacity(const CapacityRun& run) {
  std::string column = metric_column(run.metric);
  std::vector<std::vector<std::string>> rows = {
      {"mode", "threads", "fits_n", "fits_" + column + "_ms", "over_n", "over_" + column + "_ms", "points"}};
  std::string notes;
  size_t cut_round = 0;  // the round a ^C cut short, whose points count for nothing
  for (const ModeCapacity& mode : run.modes) {
    const CapacityResult& r = mode.result;
    const auto whole =
        std::count_if(mode.tried.begin(), mode.tried.end(), [](const CapacityPoint& p) { return !p.partial; });
    for (const CapacityPoint& p : mode.tried)
      if (p.partial) cut_round = std::max(cut_round, p.round);
    rows.push_back({mode.mode, std::to_string(mode.threads), r.fit ? std::to_string(r.fit->n) : "0",
                    r.fit ? fixed(r.fit->median_ms, 3) : "-", r.fail ? std::to_string(r.fail->n) : "-",
                    r.fail ? fixed(r.fail->median_ms, 3) : "-", std::to_string(whole)});
    if (r.capped)
      notes += mode.mode + ": the cap of " + std::to_string(mode.rule.cap) +
               " characters fits; the capacity may be higher\n";
    if (!r.fit && r.fail)
      notes += mode.mode + ": not even " + std::to_string(r.fail->n) + " character" + (r.fail->n == 1 ? "" : "s") +
               " fit" + (r.fail->n == 1 ? "s" : "") + "\n";
    if (r.non_monotonic)
      notes += mode.mode +
               ": a larger crowd measured more than 10% faster than a smaller one (noise, or a cost that "
               "does not grow with the crowd): the boundary found is one of several\n";
  }
  std::string out = align_columns(rows, {0});
  // Cut short: said before the table's notes and again at their end, so that
  // neither a reader of the first lines nor of the last takes it as the answer.
  std::string interrupted;
  if (run.partial) {
    const size_t rounds = cut_round > 0 ? cut_round - 1 : 0;
    interrupted = "INTERRUPTED: partial search, not capacities: round " + std::to_string(cut_round) +
                  " was cut short and left out; the table holds the " + std::to_string(rounds) + " whole round" +
                  (rounds == 1 ? "" : "s") + " before it (points: those measured whole)\n";
    out = interrupted + out;
  }
  double budget = run.modes.empty() ? 0 : run.modes.front().rule.budget_ms;
  double resolution = run.modes.empty() ? 0 : run.modes.front().rule.resolution;
  size_t start = run.modes.empty() ? 0 : run.modes.front().rule.start;
  out += "fits_n: the largest crowd whose median " + run.metric.name() + " time was at most " + fixed(budget, 3) +
         " ms; over_n: the smallest crowd above it that was over\n";
  out += "search: from " + std::to_string(start) +
         " characters, doubling while it fits, then bisection until over_n - fits_n <= max(1, " +
         fixed(resolution * 100, 1) + "% of fits_n); " + std::to_string(run.frames) + " frames per point after " +
         std::to_string(run.warmup) + " warm-up, modes interleaved in blocks of " + std::to_string(run.block) +
         " frames\n";
  return out + notes + interrupted;
}

ResultDocument capacity_document(const CapacityRun& run) {
  ResultDocument d;
  d.kind = "capacity";
  d.described = run.first;
  d.block_frames = run.block;
  d.partial = run.partial;
  CapacityRecord& c = d.capacity.emplace();
  const CapacityRule rule = run.modes.empty() ? CapacityRule{} : run.modes.front().rule;
  c.budget_ms = rule.budget_ms;
  c.metric = run.metric.name();
  c.start = rule.start;
  c.precision = rule.resolution;
  c.frames_per_point = run.frames;
  c.warmup = run.warmup;
  for (const ModeCapacity& mode : run.modes) {
    c.rows.push_back({mode.mode, static_cast<size_t>(mode.threads), mode.rule.cap, mode.result.capped,
                      mode.result.non_monotonic, mode.result.fit, mode.result.fail, mode.tried});
    for (const CapacityPoint& p : mode.tried)
      if (!p.partial) {
        ModeMedians point;
        point.mode = mode.mode;
        point.characters = p.n;
        point.frame_ms = p.frame_median_ms;
        d.sweep.push_back(point);
      }
    // The bench result at the mode's capacity (at the first size over when none fit).
    const std::optional<Result>& run_at = mode.fit_run ? mode.fit_run : mode.fail_run;
    if (run_at) d.runs.push_back(*run_at);
  }
  return d;
}

nlohmann::json capacity_to_json(const CapacityRun& run) {
  return result_document_to_json(capacity_document(run));
}

std::string capacity_svg(const CapacityRun& run) {
  ModeColours colours;
  std::string scene;
  if (run.first) scene = ": " + scene_file_name(*run.first) + ", backend " + run.first->run.backend;
  LineChart chart{"Median " + run.metric.name() + " time against crowd size" + scene,
                  "characters (log scale)",
                  "median " + run.metric.name() + " time (ms)",
                  {},
                  true,
                  true};
  chart.id = "capacity";
  for (const ModeCapacity& mode : run.modes) {
    std::vector<CapacityPoint> points;
    for (const CapacityPoint& p : mode.tried)
      if (!p.partial) points.push_back(p);
    std::sort(points.begin(), points.end(), [](const CapacityPoint& a, const CapacityPoint& b) { return a.n < b.n; });
    LineSeries series{mode.mode, {}, {}, colours.colour(mode.mode)};
    for (const CapacityPoint& p : points) {
      series.x.push_back(static_cast<double>(p.n));
      series.y.push_back(p.median_ms);
    }
    chart.series.push_back(std::move(series));
  }
  if (!run.modes.empty()) {
    double budget = run.modes.front().rule.budget_ms;
    chart.guides.push_back({budget, fixed(budget, 1) + " ms budget (" + fixed(1000.0 / budget, 0) + " fps)", "#B00020",
                            "8,4", "budget", true});
  }
  SvgDocument svg;
  svg.add(chart);
  return svg.str();
}

}  // namespace crowdprof

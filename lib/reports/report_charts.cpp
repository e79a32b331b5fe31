#include "reports/report_charts.h"

#include "reports/cost_error.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "base/number_text.h"
#include "result/result_codec.h"
#include "measuring/stats.h"

namespace crowdprof {

double median_frame_ms(const std::vector<double>& frame_ms) {
  if (frame_ms.empty()) return 0;
  std::vector<double> sorted = frame_ms;
  std::sort(sorted.begin(), sorted.end());
  return sorted[(sorted.size() - 1) / 2];
}

namespace {

std::vector<double> frame_numbers(size_t count) {
  std::vector<double> x(count);
  for (size_t i = 0; i < count; ++i) x[i] = static_cast<double>(i);
  return x;
}

std::string frames_axis(const std::vector<ReportRun>& runs) {
  std::string warmup = runs.empty() ? "0" : std::to_string(runs.front().result.run.warmup);
  return "frame (0 = the first measured, after " + warmup + " warm-up)";
}

}  // namespace

std::string report_number(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::vector<double> result_samples(const Result& result, const std::string& key) {
  const std::vector<double>* values = metric_samples(result, key);
  return values ? *values : std::vector<double>{};
}

std::string scene_file_name(const Result& result) {
  const std::string& path = !result.run.scene_file.empty() ? result.run.scene_file : result.run.file;
  if (path.empty()) return result.run.character;
  return std::filesystem::path(path).filename().string();
}

std::string scene_caption(const Result& result) {
  return scene_file_name(result) + " \u00d7 " + std::to_string(result.run.characters) + ", backend " +
         result.run.backend;
}

LineChart frame_time_chart(const std::vector<ReportRun>& runs, ModeColours& colours) {
  LineChart chart{"Frame time per frame: " + (runs.empty() ? std::string() : scene_caption(runs.front().result)),
                  frames_axis(runs),
                  "frame time (ms)",
                  {},
                  false};
  chart.id = "frame-time";
  double highest = 0;
  for (const ReportRun& run : runs) {
    std::vector<double> ms = result_samples(run.result, "frame_ms");
    for (double v : ms) highest = std::max(highest, v);
    std::string colour = colours.colour(run.label);
    struct Mark {
      const char* name;
      double q;
      const char* dash;
    };
    for (Mark mark : {Mark{"median", 0.5, "2,3"}, Mark{"p95", 0.95, "6,3"}, Mark{"p99", 0.99, "12,3"}}) {
      double value = mark.q == 0.5 ? median_frame_ms(ms) : quantile(ms, mark.q);
      std::string label =
          std::string(mark.name) + (runs.size() > 1 ? " " + run.label : "") + " " + report_number(value, 2) + " ms";
      chart.guides.push_back({value, label, colour, mark.dash, std::string("percentile ") + mark.name, true});
    }
    chart.series.push_back({run.label, frame_numbers(ms.size()), std::move(ms), colour});
  }
  // A budget far above every frame would squash the frames flat: it is then
  // named at the top of the chart instead of drawn.
  for (double budget : kBudgetsMs)
    chart.guides.push_back({budget,
                            report_number(budget, 1) + " ms budget (" + report_number(1000.0 / budget, 0) + " fps)",
                            "#B00020", "8,4", "budget", highest >= 0.4 * budget});
  // Several runs: a label for every percentile would fill the margin; the
  // legend names each kind of line by its dash (the colour is the run's), the
  // table below the chart gives the values, the lines keep their tooltips.
  if (runs.size() > 2) {
    for (Guide& guide : chart.guides)
      if (guide.kind != "budget") guide.label.clear();
    chart.keys = {{"percentile median", "median (each run's colour)", "2,3"},
                  {"percentile p95", "p95 (each run's colour)", "6,3"},
                  {"percentile p99", "p99 (each run's colour)", "12,3"}};
  }
  return chart;
}

StackedArea categories_chart(const ReportRun& run) {
  StackedArea chart{"Time per category per frame, " + run.label + ": " + scene_caption(run.result),
                    frames_axis({run}),
                    "time (ms), categories stacked",
                    {},
                    {}};
  chart.id = "categories";
  chart.x = frame_numbers(run.result.frames());
  for (size_t c = 0; c < kCategoryCount; ++c) {
    auto category = static_cast<Category>(c);
    std::vector<double> ms = result_samples(run.result, series_name(category));
    if (std::none_of(ms.begin(), ms.end(), [](double v) { return v > 0; })) continue;
    chart.layers.push_back({std::string(category_name(category)), category_colour(category), std::move(ms)});
  }
  return chart;
}

std::vector<CostErrorPoint> run_costs(const std::vector<ReportRun>& runs) {
  std::vector<CostErrorInput> inputs;
  for (const ReportRun& run : runs)
    inputs.push_back({run.label, quantile(result_samples(run.result, "frame_ms"), 0.5),
                      quantile(result_samples(run.result, series_name(Category::Animations)), 0.5),
                      run.result.drawn_error, run.result.run.characters});
  return cost_error_points(inputs);
}

std::optional<LineChart> cost_error_chart(const std::vector<CostErrorPoint>& points, ModeColours& colours) {
  if (points.empty()) return std::nullopt;
  LineChart chart{"Cost against error: median frame, largest drawn error on screen",
                  "median frame time (ms)",
                  "largest drawn error (px)",
                  {},
                  true};
  chart.id = "cost-error";
  // The front first, so that each mode's dot is drawn over it.
  std::vector<const CostErrorPoint*> front;
  for (const CostErrorPoint& p : points)
    if (p.front) front.push_back(&p);
  std::sort(front.begin(), front.end(), [](auto* a, auto* b) { return a->frame_ms < b->frame_ms; });
  LineSeries line{"Pareto front", {}, {}, "#767676"};
  for (const CostErrorPoint* p : front) {
    line.x.push_back(p->frame_ms);
    line.y.push_back(p->error.max_px);
  }
  chart.series.push_back(std::move(line));
  for (const CostErrorPoint& p : points)
    chart.series.push_back(
        {p.past_threshold ? p.mode + " (past " + report_number(kFrontMaxErrorPx, 0) + " px)" : p.mode,
         {p.frame_ms},
         {p.error.max_px},
         colours.colour(p.mode)});
  return chart;
}

std::optional<LineChart> advice_chart(const AdviceRecord& advice) {
  if (advice.steps.empty() || advice.steps.front().candidates.empty()) return std::nullopt;
  LineChart chart{"Cost against error: every configuration advise measured, and the path it took",
                  "largest drawn error (px; at most " + shortest_text(advice.max_error_px) + " allowed)",
                  advice.metric + " median (ms)",
                  {},
                  true};
  chart.id = "advice";
  const AdviceCandidate& start = advice.steps.front().candidates.front();
  LineSeries path{"the path taken", {start.error_px}, {start.metric.median}, "#222222"};
  std::vector<LineSeries> levers;
  for (const AdviceStep& step : advice.steps) {
    if (step.taken) {
      path.x.push_back(step.candidates[*step.taken].error_px);
      path.y.push_back(step.candidates[*step.taken].metric.median);
    }
    // The base is the configuration of the moment (on the path); a lever
    // that could not run was not measured.
    for (size_t c = 1; c < step.candidates.size(); ++c) {
      const AdviceCandidate& candidate = step.candidates[c];
      if (candidate.metric.median <= 0 || candidate.verdict.rfind("cannot run", 0) == 0) continue;
      auto it =
          std::find_if(levers.begin(), levers.end(), [&](const LineSeries& s) { return s.name == candidate.lever; });
      if (it == levers.end()) it = levers.insert(levers.end(), LineSeries{candidate.lever, {}, {}, {}, false});
      it->x.push_back(candidate.error_px);
      it->y.push_back(candidate.metric.median);
    }
  }
  chart.series.push_back(std::move(path));
  for (LineSeries& lever : levers) chart.series.push_back(std::move(lever));
  chart.guides.push_back(
      {advice.budget_ms, "budget " + significant(advice.budget_ms, 3) + " ms", "#B00020", "8,4", "budget", true});
  return chart;
}

StackedBars modes_chart(const std::vector<ReportRun>& runs) {
  std::vector<std::array<double, kCategoryCount>> medians;
  for (const ReportRun& run : runs) {
    medians.emplace_back();
    for (size_t c = 0; c < kCategoryCount; ++c)
      medians.back()[c] = quantile(result_samples(run.result, series_name(static_cast<Category>(c))), 0.5);
  }
  StackedBars chart{"Median time per category, modes side by side: " +
                        (runs.empty() ? std::string() : scene_caption(runs.front().result)),
                    "median time (ms)",
                    {},
                    {},
                    {}};
  chart.id = "modes";
  std::vector<size_t> shown;
  for (size_t c = 0; c < kCategoryCount; ++c)
    if (std::any_of(medians.begin(), medians.end(), [c](const auto& m) { return m[c] >= 0.005; })) {
      shown.push_back(c);
      chart.segments.emplace_back(category_name(static_cast<Category>(c)));
      chart.colours.emplace_back(category_colour(static_cast<Category>(c)));
    }
  for (size_t r = 0; r < runs.size(); ++r) {
    chart.bars.push_back(runs[r].label);
    std::vector<double> values;
    for (size_t c : shown) values.push_back(medians[r][c]);
    chart.values.push_back(std::move(values));
  }
  return chart;
}

LineChart sweep_chart(const std::vector<SweepPoint>& points, SweepAxis axis, const std::string& caption,
                      ModeColours& colours, std::optional<double> budget_ms) {
  const bool passes = axis == SweepAxis::Passes;
  LineChart chart{(passes ? "Median frame time against passes: " : "Median frame time against crowd size: ") + caption,
                  passes ? "passes (draws of the crowd a frame)" : "characters (log scale)",
                  "median frame time (ms)",
                  {},
                  true};
  chart.log_x = !passes;
  chart.id = "sweep";
  for (const SweepPoint& point : points) {
    auto it = std::find_if(chart.series.begin(), chart.series.end(),
                           [&](const LineSeries& s) { return s.name == point.mode; });
    if (it == chart.series.end())
      it = chart.series.insert(chart.series.end(), LineSeries{point.mode, {}, {}, colours.colour(point.mode)});
    it->x.push_back(static_cast<double>(point.x));
    it->y.push_back(point.frame_median_ms);
  }
  for (LineSeries& series : chart.series) {  // left to right, whatever order the points came in
    std::vector<size_t> order(series.x.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return series.x[a] < series.x[b]; });
    LineSeries sorted{series.name, {}, {}, series.colour};
    for (size_t i : order) sorted.x.push_back(series.x[i]), sorted.y.push_back(series.y[i]);
    series = std::move(sorted);
  }
  if (budget_ms)
    chart.guides.push_back(
        {*budget_ms, report_number(*budget_ms, 1) + " ms budget (" + report_number(1000.0 / *budget_ms, 0) + " fps)",
         "#B00020", "8,4", "budget", true});
  return chart;
}

VerdictChart verdict_chart(const CheckResult& result, const CheckOptions& options) {
  VerdictChart chart{"check: change of each metric's median, baseline to current", {}};
  chart.id = "verdict";
  for (const MetricCheck& m : result.metrics) {
    // The words format_check uses for the same outcomes.
    std::string verdict = !m.tested     ? "not tested"
                          : m.regressed ? "REGRESSION"
                          : m.excused   ? "slower, a warning (the same instructions per frame)"
                          : m.beyond_tolerance && !m.beyond_floor ? "slower, under the floor"
                          : m.beyond_tolerance                    ? "slower, not significant"
                          : significantly_faster(m, options)      ? "faster"
                                                                  : "ok";
    std::string colour = !m.tested                         ? "#767676"
                         : m.regressed                     ? "#B00020"
                         : m.excused || m.beyond_tolerance ? "#A66A00"
                                                           : "#1B7F3B";
    const std::string unit = " " + m.value_unit;
    std::string detail = m.metric + ": median " + metric_value_text(m, m.baseline.median) + " -> " +
                         metric_value_text(m, m.current.median) + unit +
                         (m.tested ? ", p = " + report_number(m.p_adjusted, 4) + " (Holm), floor " +
                                         metric_value_text(m, m.floor_ms) + unit
                                   : " (measured apart: not tested)");
    // A slowdown must pass both the tolerance and the floor: the band is the larger.
    double allowed = std::max(options.tolerance, m.baseline.median > 0 ? m.floor_ms / m.baseline.median : 0.0);
    chart.rows.push_back({m.metric, m.change, verdict, colour, detail, allowed});
  }
  return chart;
}

}  // namespace crowdprof

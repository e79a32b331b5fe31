#include "reports/compare_report.h"

#include "reports/cost_error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "reports/chart_colours.h"
#include "reports/report_charts.h"
#include "measuring/stats.h"
#include "reports/svg_chart.h"
#include "base/number_text.h"
#include "reports/text_table.h"
#include "result/result_codec.h"

namespace crowdprof {

namespace {

std::vector<double> frame_ms(const Result& run) {
  std::vector<double> out;
  for (const FrameRecord& f : run.frame_records) out.push_back(f.times.total_ms());
  return out;
}

}  // namespace

bool is_main_point(const Comparison& comparison, const Result& run) {
  if (comparison.runs.empty()) return false;
  const RunDescription& main = comparison.runs.front().run;
  return comparison.sweep_axis == SweepAxis::Passes ? run.run.switches.passes == main.switches.passes
                                                    : run.run.characters == main.characters;
}

std::vector<ModeMedians> mode_medians(const std::vector<Result>& runs) {
  std::vector<ModeMedians> out;
  std::map<std::pair<size_t, uint32_t>, double> first_at_size;  // (characters, passes) -> first mode's median
  for (const Result& run : runs) {
    ModeMedians m;
    m.mode = run.run.mode;
    m.characters = run.run.characters;
    m.passes = run.run.switches.passes;
    m.threads = run.run.threads;
    std::vector<double> totals = frame_ms(run);
    m.frame_ms = summarize(totals).median;
    for (size_t c = 0; c < kCategoryCount; ++c) {
      std::vector<double> values;
      for (const FrameRecord& f : run.frame_records) values.push_back(f.times.ms[c]);
      m.category_ms[c] = summarize(values).median;
    }
    auto [first, inserted] = first_at_size.emplace(std::pair(m.characters, m.passes), m.frame_ms);
    m.speedup = m.frame_ms > 0 ? first->second / m.frame_ms : 0.0;
    m.digest = run.digest;
    m.counters = run.counters.values;  // the medians over frames, as the run's JSON
    out.push_back(m);
  }
  return out;
}

std::vector<Category> shown_categories(const std::vector<ModeMedians>& medians) {
  std::vector<Category> shown;
  for (size_t c = 0; c < kCategoryCount; ++c)
    if (std::any_of(medians.begin(), medians.end(), [c](const ModeMedians& m) { return m.category_ms[c] >= 0.005; }))
      shown.push_back(static_cast<Category>(c));
  return shown;
}

std::vector<Category> table_categories(const std::vector<Result>& runs) {
  std::vector<Category> shown = {Category::Logic,      Category::Animations, Category::Scenegraph,
                                 Category::Rasterizer, Category::Overhead,   Category::Outside};
  // Drawn: a GL backend, or draw calls (a run not made by a command records none).
  auto drew = [](const Result& run) {
    return run.run.backend != "none" || std::any_of(run.frame_records.begin(), run.frame_records.end(),
                                                    [](const FrameRecord& f) { return f.counters.draw_calls > 0; });
  };
  if (std::any_of(runs.begin(), runs.end(), drew))
    shown.push_back(Category::GpuLatency);  // last, as bench's profile lists it
  return shown;
}

namespace {

// Each mode's medians and drawn error, for the cost/error table and chart.
std::vector<CostErrorPoint> comparison_costs(const Comparison& comparison, const std::vector<ModeMedians>& medians) {
  std::vector<CostErrorInput> costs;
  for (size_t r = 0; r < medians.size() && r < comparison.runs.size(); ++r)
    costs.push_back({medians[r].mode, medians[r].frame_ms,
                     medians[r].category_ms[static_cast<size_t>(Category::Animations)],
                     comparison.runs[r].drawn_error});
  return cost_error_points(costs);
}

}  // namespace

std::string format_comparison(const Comparison& comparison) {
  std::vector<ModeMedians> medians = mode_medians(comparison.runs);
  std::vector<Category> shown = table_categories(comparison.runs);
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> header = {"mode", "characters", "threads", "frame_ms"};
  for (Category c : shown) header.push_back(std::string(category_column(c)) + "_ms");
  // The GPU's own time (timer queries) beside the categories, when any mode has it.
  std::vector<std::vector<double>> gpu(comparison.runs.size());
  bool any_gpu = false;
  for (size_t r = 0; r < comparison.runs.size(); ++r) {
    for (const FrameRecord& f : comparison.runs[r].frame_records)
      if (std::isfinite(f.gpu_ms)) gpu[r].push_back(f.gpu_ms);
    any_gpu = any_gpu || !gpu[r].empty();
  }
  if (any_gpu) header.push_back("gpu_ms");
  for (const char* tail : {"speedup_x", "copies_culled", "digest"}) header.push_back(tail);
  rows.push_back(header);
  for (size_t r = 0; r < medians.size(); ++r) {
    const ModeMedians& m = medians[r];
    const Result& run = comparison.runs[r];
    std::vector<std::string> row = {m.mode, std::to_string(m.characters), std::to_string(m.threads),
                                    fixed(m.frame_ms, 3)};
    for (Category c : shown) row.push_back(fixed(m.category_ms[static_cast<size_t>(c)], 3));
    if (any_gpu) {
      // Below the timer's resolution: "<" it, not a number read as measured.
      double median = gpu[r].empty() ? 0 : summarize(gpu[r]).median, resolution = run.run.gpu_timer_resolution_ms;
      std::string cell = gpu[r].empty() ? "n/a" : fixed(median, 3);
      if (!gpu[r].empty() && resolution > 0 && median < resolution) (cell = "<") += fixed(resolution, 4);
      row.push_back(cell);
    }
    uint64_t culled = run.counters.values.copies_culled;
    row.push_back(fixed(m.speedup, 2));
    row.push_back(std::to_string(culled));
    row.push_back(run.digest);
    rows.push_back(row);
  }
  std::string out = align_columns(rows, {0, rows.front().size() - 1});
  if (!comparison.runs.empty())
    out += "median of " + std::to_string(comparison.runs.front().frame_records.size()) +
           " frames per mode, run in blocks of " + std::to_string(comparison.block) +
           " frames; speedup_x = " + comparison.runs.front().run.mode + "'s frame_ms / the mode's\n";
  out += format_cost_error(comparison_costs(comparison, medians));
  if (comparison.sweep.empty()) return out;
  rows.clear();
  const SweepAxis axis = comparison.sweep_axis;
  rows.push_back({std::string(to_string(axis)), "mode", "frame_ms", "speedup_x"});
  for (const ModeMedians& m : mode_medians(comparison.sweep))
    rows.push_back({std::to_string(m.on(axis)), m.mode, fixed(m.frame_ms, 3), fixed(m.speedup, 2)});
  return out +
         (axis == SweepAxis::Passes ? "\nsweep: median frame time by passes (draws of the crowd a frame)\n"
                                    : "\nsweep: median frame time by crowd size\n") +
         align_columns(rows, {1});
}

void write_comparison_csv(const Comparison& comparison, std::ostream& out) {
  bool first = true;
  auto write = [&](const Result& run) {
    std::ostringstream rows;
    write_csv(run, rows);
    std::string text = rows.str();
    out << (first ? text : text.substr(text.find('\n') + 1));
    first = false;
  };
  for (const Result& run : comparison.runs) write(run);
  // The sweep's runs at the main point are the main runs: written once.
  for (const Result& run : comparison.sweep)
    if (!is_main_point(comparison, run)) write(run);
}

ResultDocument comparison_document(const Comparison& comparison) {
  ResultDocument d;
  d.kind = "compare";
  d.runs = comparison.runs;
  d.summary = mode_medians(comparison.runs);
  d.sweep = mode_medians(comparison.sweep);
  d.sweep_axis = comparison.sweep_axis;
  d.block_frames = comparison.block;
  d.partial = !comparison.runs.empty() && comparison.runs.front().partial;
  return d;
}

nlohmann::json comparison_to_json(const Comparison& comparison) {
  return result_document_to_json(comparison_document(comparison));
}

std::string comparison_svg(const Comparison& comparison) {
  SvgDocument svg;
  ModeColours colours;
  std::string scene, sweep_scene, warmup = "0";
  if (!comparison.runs.empty()) {
    const RunDescription& run = comparison.runs.front().run;
    const std::string file = scene_file_name(comparison.runs.front());  // the file, not the root node
    scene = ": " + file + " \u00d7 " + std::to_string(run.characters) + " (" + std::to_string(run.joints) +
            " joints, " + std::to_string(run.vertices) + " vertices), backend " + run.backend;
    sweep_scene = ": " + file + ", backend " + run.backend;
    warmup = std::to_string(run.warmup);
  }
  LineChart frames{"Frame time per frame" + scene,
                   "frame (0 = the first measured, after " + warmup + " warm-up)",
                   "frame time (ms)",
                   {},
                   false};
  for (const Result& run : comparison.runs) {
    LineSeries series{run.run.mode, {}, frame_ms(run), colours.colour(run.run.mode)};
    for (size_t i = 0; i < series.y.size(); ++i) series.x.push_back(static_cast<double>(i));
    frames.series.push_back(std::move(series));
  }
  svg.add(frames);

  std::vector<ModeMedians> medians = mode_medians(comparison.runs);
  StackedBars bars{"Median time per category" + scene, "median time (ms)", {}, {}, {}};
  std::vector<Category> shown = shown_categories(medians);
  for (Category c : shown) {
    bars.segments.emplace_back(category_name(c));
    bars.colours.emplace_back(category_colour(c));
  }
  for (const ModeMedians& m : medians) {
    bars.bars.push_back(m.mode);
    std::vector<double> values;
    for (Category c : shown) values.push_back(m.category_ms[static_cast<size_t>(c)]);
    bars.values.push_back(values);
  }
  svg.add(bars);
  if (std::optional<LineChart> costs = cost_error_chart(comparison_costs(comparison, medians), colours)) {
    costs->title += scene;
    svg.add(*costs);
  }

  if (!comparison.sweep.empty()) {
    std::vector<SweepPoint> points;
    for (const ModeMedians& m : mode_medians(comparison.sweep))
      points.push_back({m.mode, m.on(comparison.sweep_axis), m.frame_ms});
    LineChart sweep = sweep_chart(points, comparison.sweep_axis,
                                  sweep_scene.substr(std::min<size_t>(2, sweep_scene.size())), colours, std::nullopt);
    sweep.id.clear();
    svg.add(sweep);
  }
  return svg.str();
}

}  // namespace crowdprof

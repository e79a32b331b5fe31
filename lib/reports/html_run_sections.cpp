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

// Milliseconds in a profile cell: two decimals, more under a millisecond so
// that a fast run's categories do not all read 0.00.
std::string ms_cell(double ms) {
  if (ms == 0 || !std::isfinite(ms) || std::abs(ms) >= 1) return report_number(ms, 2);
  return report_number(ms, std::abs(ms) >= 0.1 ? 3 : 4);
}

// The switches a result records, in the table's order as options spell them
// ("--culling on, --index-order optimized"): words a narrow page can wrap.
std::string switches_line(const ModeSwitches& switches) {
  const nlohmann::json recorded = switches_to_json(switches);
  std::string line;
  for (const SwitchSpec& spec : switch_table())
    if (recorded.contains(std::string(spec.name)))
      line +=
          (line.empty() ? "" : ", ") + option_spelling(spec.name) + " " + switch_text(recorded[std::string(spec.name)]);
  return line;
}

// Rows of what a run was measured on: the machine and build the result recorded,
// which GL drew, the threads, the mode and crowdprof's version.
std::vector<std::pair<std::string, std::string>> environment_rows(const Result& result) {
  const Environment& e = result.environment;
  const RunDescription& run = result.run;
  return {{"crowdprof", e.version + " (" + e.commit + ")"},
          {"backend", run.backend},
          {"build_type", e.build_type},
          {"compiler", e.compiler},
          {"cores", std::to_string(e.cores)},
          {"cpu", e.cpu},
          {"renderer", run.renderer},
          {"simd", e.simd},
          {"threads", std::to_string(run.threads)},
          {"mode", run.mode + ": " + switches_line(run.switches)}};
}

// The rows of counters: a row per counter, a column per run (blank where a
// run did not record it).
std::string counter_rows(const std::vector<ReportRun>& runs, const std::vector<size_t>& rows) {
  std::string out = "<table class=\"counters\"><tr><th class=\"name\">counter (per frame, median)</th>";
  for (const ReportRun& run : runs) out += "<th class=\"run\">" + html_text(run.label) + "</th>";
  out += "</tr>\n";
  for (size_t i : rows) {
    out += "<tr><td class=\"name\">" + html_text(std::string(kCounterFields[i].name)) + "</td>";
    for (const ReportRun& run : runs)
      out += "<td>" +
             (run.result.counters.present[i] ? with_thousands(run.result.counters.values.*kCounterFields[i].member)
                                             : std::string()) +
             "</td>";
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

// Each run's median frame (the frame whose total is the median), by category.
std::vector<FrameTimes> median_frames(const std::vector<ReportRun>& runs) {
  std::vector<FrameTimes> medians;
  for (const ReportRun& run : runs) {
    std::vector<FrameRecord> frames(run.result.frames());
    for (size_t c = 0; c < kCategoryCount; ++c) {
      const std::vector<double>& ms = run.result.samples.category_ms[c];
      for (size_t i = 0; i < frames.size(); ++i) frames[i].times.ms[c] = ms[i];
    }
    medians.push_back(frames[median_frame(frames)].times);
  }
  return medians;
}

// The GPU's own time (GL timer queries), beside the categories and not one of
// them: n/a with the reason where it was not measured, never 0. {value, how},
// as HTML (the reason, read from the result, escaped).
std::pair<std::string, std::string> gpu_time_cells(const ReportRun& run) {
  const RunDescription& described = run.result.run;
  const std::vector<double>& gpu = run.result.samples.gpu_ms;
  bool timed = std::any_of(gpu.begin(), gpu.end(), [](double ms) { return std::isfinite(ms); });
  double median = metric_median(run.result, "gpu_ms");
  if (timed && described.gpu_timer_resolution_ms > 0 && median < described.gpu_timer_resolution_ms)
    return {"-", "below the timer's resolution"};
  if (timed) return {ms_cell(median), "timer queries"};
  return {"n/a", html_text(described.gpu_timing_missing.empty() ? "not recorded" : described.gpu_timing_missing)};
}

std::string swatch(Category category) {
  return "<span class=\"swatch\" style=\"background:" + std::string(category_colour(category)) + "\"></span>";
}

// The BGE's overlay, a column pair (ms, share) per run: for a few runs.
std::string profile_by_category(const std::vector<ReportRun>& runs, const std::vector<FrameTimes>& medians) {
  std::string out = "<table><tr><th class=\"name\">category</th>";
  for (const ReportRun& run : runs) out += "<th>" + html_text(run.label) + " ms</th><th>%</th>";
  out += "</tr>\n<tr><td class=\"name\"><b>Frametime</b></td>";
  for (const FrameTimes& t : medians)
    out += "<td><b>" + ms_cell(t.total_ms()) + "</b></td><td>" +
           (t.total_ms() > 0 ? report_number(1000.0 / t.total_ms(), 1) : "-") + " fps</td>";
  out += "</tr>\n";
  for (size_t c = 0; c < kCategoryCount; ++c) {
    auto category = static_cast<Category>(c);
    out += "<tr><td class=\"name\">" + swatch(category) + html_text(std::string(category_name(category))) + "</td>";
    for (const FrameTimes& t : medians) {
      double share = t.total_ms() > 0 ? t.ms[c] / t.total_ms() : 0.0;
      out += "<td>" + ms_cell(t.ms[c]) + "</td><td class=\"name\">" + report_number(share * 100, 0) +
             "% <span class=\"bar\" style=\"width:" + report_number(share * 60, 1) +
             "px;background:" + category_colour(category) + "\"></span></td>";
    }
    out += "</tr>\n";
  }
  out += "<tr class=\"gpu-time\"><td class=\"name\">GPU time (median)</td>";
  for (const ReportRun& run : runs) {
    auto [value, how] = gpu_time_cells(run);
    out += "<td>" + value + "</td><td class=\"name\">" + how + "</td>";
  }
  return out + "</tr>\n</table>\n";
}

// The same, a row per run and a column per category that took time: for more
// runs than fit side by side at 1280 px (a compare of every mode).
std::string profile_by_run(const std::vector<ReportRun>& runs, const std::vector<FrameTimes>& medians) {
  std::vector<size_t> shown;
  for (size_t c = 0; c < kCategoryCount; ++c)
    if (std::any_of(medians.begin(), medians.end(), [c](const FrameTimes& t) { return t.ms[c] >= 0.005; }))
      shown.push_back(c);
  std::string out = "<table class=\"by-run\"><tr><th class=\"name\">run</th><th>Frametime ms</th><th>fps</th>";
  for (size_t c : shown)
    out += "<th>" + swatch(static_cast<Category>(c)) + html_text(std::string(category_name(static_cast<Category>(c)))) +
           "</th>";
  out += "<th>GPU time</th></tr>\n";
  for (size_t r = 0; r < runs.size(); ++r) {
    const FrameTimes& t = medians[r];
    out += "<tr><td class=\"name\">" + html_text(runs[r].label) + "</td><td><b>" + ms_cell(t.total_ms()) +
           "</b></td><td>" + (t.total_ms() > 0 ? report_number(1000.0 / t.total_ms(), 1) : "-") + "</td>";
    for (size_t c : shown) out += "<td>" + ms_cell(t.ms[c]) + "</td>";
    auto [value, how] = gpu_time_cells(runs[r]);
    out += "<td title=\"" + how + "\">" + value + "</td></tr>\n";
  }
  return out + "</table>\n<p>ms of each run's median frame; categories under 0.005 ms in every run are left out.</p>\n";
}

// What each run was: its crowd, frames and digest.
std::string runs_table(const std::vector<ReportRun>& runs) {
  std::string out =
      "<table class=\"runs\"><tr><th class=\"name\">run</th><th>characters</th><th>joints</th>"
      "<th>vertices</th><th>frames</th><th>warm-up</th><th class=\"name\">actions</th>"
      "<th class=\"name\">scene</th><th class=\"name\">digest</th></tr>\n";
  for (const ReportRun& run : runs) {
    const RunDescription& scene = run.result.run;
    out += "<tr><td class=\"name\">" + html_text(run.label) + "</td><td>" + std::to_string(scene.characters) +
           "</td><td>" + std::to_string(scene.joints) + "</td><td>" + std::to_string(scene.vertices) + "</td><td>" +
           std::to_string(run.result.frames()) + "</td><td>" + std::to_string(scene.warmup) +
           "</td><td class=\"name\">" + html_text(scene.action_choice) + "</td><td class=\"name\" title=\"" +
           html_text(scene.file) + "\">" + html_text(path_file_name(scene.file)) + "</td><td class=\"name\">" +
           html_text(run.result.digest) + "</td></tr>\n";
  }
  return out + "</table>\n";
}

// Runs whose profile columns fit side by side at 1280 px.
constexpr size_t kRunsSideBySide = 4;

}  // namespace

void label_runs(std::vector<ReportRun>& all) {
  std::vector<ReportRun*> runs;
  for (ReportRun& run : all)
    if (run.label.empty()) runs.push_back(&run);
  auto key = [](const ReportRun& r, int level) {
    std::string mode = r.result.run.mode;
    if (level == 0) return mode;
    std::string sized = mode + " n=" + std::to_string(r.result.run.characters);
    return level == 1 ? sized : sized + " (" + path_file_name(r.source) + ")";
  };
  for (int level = 0; level < 3; ++level) {
    std::map<std::string, int> seen;
    for (const ReportRun* r : runs) ++seen[key(*r, level)];
    if (std::all_of(seen.begin(), seen.end(), [](const auto& s) { return s.second == 1; }) || level == 2) {
      std::map<std::string, int> count;
      for (ReportRun* r : runs) {
        r->label = key(*r, level);
        if (seen[r->label] > 1) r->label += " #" + std::to_string(++count[r->label]);
      }
      return;
    }
  }
}

std::string environment_section(const std::vector<ReportRun>& runs) {
  // One column when every run was measured alike, else one per run.
  std::vector<std::vector<std::pair<std::string, std::string>>> tables;
  for (const ReportRun& run : runs) tables.push_back(environment_rows(run.result));
  bool alike = std::all_of(tables.begin(), tables.end(), [&](const auto& t) {
    auto skip_mode = [](const auto& rows) {
      std::vector<std::pair<std::string, std::string>> out;
      for (const auto& row : rows)
        if (row.first != "mode" && row.first != "threads") out.push_back(row);
      return out;
    };
    return skip_mode(t) == skip_mode(tables.front());
  });
  std::string out = "<section id=\"environment\"><h2>Environment</h2>\n<table><tr><th class=\"name\">field</th>";
  size_t columns = alike ? 1 : runs.size();
  for (size_t c = 0; c < columns; ++c)
    out += "<th class=\"name\">" + html_text(alike ? "value" : runs[c].label) + "</th>";
  out += "</tr>\n";
  std::vector<std::string> keys;
  for (const auto& table : tables)
    for (const auto& row : table)
      if (std::find(keys.begin(), keys.end(), row.first) == keys.end()) keys.push_back(row.first);
  for (const std::string& key : keys) {
    out += "<tr><td class=\"name\">" + html_text(key) + "</td>";
    if (alike && (key == "mode" || key == "threads")) {
      // Each run's, in the runs' order, a line each (a value once).
      std::vector<std::string> values;
      for (const auto& table : tables)
        for (const auto& row : table)
          if (row.first == key && std::find(values.begin(), values.end(), row.second) == values.end())
            values.push_back(row.second);
      std::string joined;
      for (const std::string& v : values) joined += (joined.empty() ? "" : "<br>") + html_text(v);
      out += "<td class=\"name\">" + joined + "</td>";
    } else {
      for (size_t c = 0; c < columns; ++c) {
        std::string value;
        for (const auto& row : tables[c])
          if (row.first == key) value = row.second;
        out += "<td class=\"name\">" + html_text(value) + "</td>";
      }
    }
    out += "</tr>\n";
  }
  return out + "</table></section>\n";
}

std::string counters_section(const std::vector<ReportRun>& runs) {
  std::vector<size_t> counted, zero;
  for (size_t i = 0; i < kCounterFields.size(); ++i) {
    bool present = false, above_zero = false;
    for (const ReportRun& run : runs)
      if (run.result.counters.present[i]) {
        present = true;
        above_zero = above_zero || run.result.counters.values.*kCounterFields[i].member != 0;
      }
    if (present) (above_zero ? counted : zero).push_back(i);
  }
  if (counted.empty() && zero.empty()) return {};
  std::string out = "<section id=\"counters\"><h2>Counters (per frame, the median over frames)</h2>\n";
  if (!counted.empty()) out += counter_rows(runs, counted);
  if (!zero.empty())
    out += "<details class=\"zero-counters\"><summary>" + std::to_string(zero.size()) +
           (zero.size() == 1 ? " counter was" : " counters were") + " zero in every run</summary>\n" +
           counter_rows(runs, zero) + "</details>\n";
  return out + "</section>\n";
}

std::string headline_section(const std::vector<ReportRun>& runs) {
  std::string out =
      "<section id=\"headline\"><table class=\"headline\"><tr><th class=\"name\">run</th>"
      "<th>median frame</th><th>p95</th><th>p99</th><th>fps (median)</th></tr>\n";
  for (const ReportRun& run : runs) {
    const std::vector<double>& ms = run.result.samples.frame_ms;
    const double median = median_frame_ms(ms);
    out += "<tr><td class=\"name\">" + html_text(run.label) + "</td><td class=\"key\">" + duration_text(median) +
           "</td><td>" + duration_text(quantile(ms, 0.95)) + "</td><td>" + duration_text(quantile(ms, 0.99)) +
           "</td><td>" + (median > 0 ? significant(1000.0 / median, 3) : "-") + "</td></tr>\n";
  }
  return out + "</table></section>\n";
}

std::string profile_section(const std::vector<ReportRun>& runs) {
  const std::vector<FrameTimes> medians = median_frames(runs);
  return "<section id=\"profile\"><h2>Profile (the BGE's table, median frame)</h2>\n" +
         (runs.size() > kRunsSideBySide ? profile_by_run(runs, medians) : profile_by_category(runs, medians)) +
         runs_table(runs) + "</section>\n";
}

std::string gpu_passes_section(const std::vector<ReportRun>& runs) {
  if (std::none_of(runs.begin(), runs.end(),
                   [](const ReportRun& r) { return !r.result.samples.gpu_pass_ms[0].empty(); }))
    return {};
  std::string out =
      "<section id=\"gpu-passes\"><h2>GPU time by pass (median a frame)</h2>\n<table><tr>"
      "<th class=\"name\">run</th><th class=\"name\">pass</th><th>GPU ms</th>";
  for (std::string_view stat : kPipelineStatNames) {
    std::string name(stat);
    std::replace(name.begin(), name.end(), '_', ' ');
    out += "<th>" + html_text(name) + "</th>";
  }
  out += "<th>invocations per vertex drawn</th></tr>\n";
  for (const ReportRun& run : runs) {
    const Result& r = run.result;
    if (r.samples.gpu_pass_ms[0].empty()) continue;
    const GpuPassMedians medians = gpu_pass_medians(r.samples.gpu_pass_ms, r.run.switches.passes);
    const double sum = medians.sum;
    for (size_t p = 0; p < kGpuPassCount; ++p) {
      if (!pass_drawn(static_cast<GpuPass>(p), r.run.switches.passes)) continue;
      out += "<tr><td class=\"name\">" + html_text(run.label) + "</td><td class=\"name\">" +
             std::string(kGpuPassNames[p]) + "</td><td>" +
             (medians.median[p] ? report_number(*medians.median[p], 3) : std::string("n/a")) + "</td>";
      if (r.pipeline_statistics) {
        for (size_t s = 0; s < kPipelineStatCount; ++s)
          out += "<td>" + with_thousands(static_cast<uint64_t>((*r.pipeline_statistics)[p][s])) + "</td>";
        const double reuse = r.invocations_per_vertex_drawn ? (*r.invocations_per_vertex_drawn)[p] : std::nan("");
        out += "<td>" + (std::isfinite(reuse) ? report_number(reuse, 3) : std::string("-")) + "</td>";
      } else {
        out +=
            "<td class=\"name\" colspan=\"" + std::to_string(kPipelineStatCount + 1) + "\">unavailable: " +
            html_text(r.run.pipeline_statistics_missing.empty() ? "not recorded" : r.run.pipeline_statistics_missing) +
            "</td>";
      }
      out += "</tr>\n";
    }
    double gpu = metric_median(r, "gpu_ms");
    out +=
        "<tr><td class=\"name\">" + html_text(run.label) + "</td><td class=\"name\"><i>passes together</i></td><td>" +
        report_number(sum, 3) + "</td><td class=\"name\" colspan=\"" + std::to_string(kPipelineStatCount + 1) + "\">" +
        (gpu > 0 ? report_number(100.0 * sum / gpu, 0) + "% of the frame's GPU time (" + report_number(gpu, 3) + " ms)"
                 : std::string("the frame's GPU time is not known")) +
        "</td></tr>\n";
  }
  return out + "</table></section>\n";
}

std::string animation_stages_section(const std::vector<ReportRun>& runs) {
  if (std::none_of(runs.begin(), runs.end(), [](const ReportRun& r) { return animation_split(r.result).has_value(); }))
    return {};
  std::string out =
      "<section id=\"animation-stages\"><h2>Animations by stage (thread time, median a frame)</h2>\n"
      "<p>Each stage's time summed over the threads that ran it; on one thread they add up to "
      "Animations, less what the pose update spends between stages.</p>\n<table><tr>"
      "<th class=\"name\">run</th>";
  for (std::string_view label : kAnimationStageLabels) out += "<th>" + std::string(label) + " ms</th>";
  out += "<th>threads</th><th>of Animations' thread time</th></tr>\n";
  for (const ReportRun& run : runs) {
    std::optional<AnimationSplit> split = animation_split(run.result);
    if (!split) continue;
    out += "<tr><td class=\"name\">" + html_text(run.label) + "</td>";
    for (size_t st = 0; st < kAnimationStageCount; ++st)
      out += "<td>" + report_number(split->median_ms[st], 3) + " (" + report_number(100.0 * split->share[st], 0) +
             "%)</td>";
    out += "<td>" + std::to_string(split->threads) + "</td><td>" + report_number(100.0 * split->coverage, 0) +
           "%</td></tr>\n";
  }
  return out + "</table></section>\n";
}

std::string percentile_table(const std::vector<ReportRun>& runs) {
  std::string out =
      "<table><tr><th class=\"name\">run</th><th>frames</th><th>median ms</th><th>p95 ms</th><th>p99 ms</th>"
      "<th>max ms</th><th>over 16.7 ms</th><th>over 33.3 ms</th></tr>\n";
  for (const ReportRun& run : runs) {
    const std::vector<double>& ms = run.result.samples.frame_ms;
    auto over = [&](double budget) {
      return std::count_if(ms.begin(), ms.end(), [&](double v) { return v > budget; });
    };
    out += "<tr><td class=\"name\">" + html_text(run.label) + "</td><td>" + std::to_string(ms.size()) + "</td><td>" +
           report_number(median_frame_ms(ms), 3) + "</td><td>" + report_number(quantile(ms, 0.95), 3) + "</td><td>" +
           report_number(quantile(ms, 0.99), 3) + "</td><td>" +
           report_number(*std::max_element(ms.begin(), ms.end()), 3) + "</td><td>" +
           std::to_string(over(kBudgetsMs[0])) + "</td><td>" + std::to_string(over(kBudgetsMs[1])) + "</td></tr>\n";
  }
  return out + "</table>\n";
}

std::string modes_table(const std::vector<ReportRun>& runs) {
  std::string out =
      "<table><tr><th class=\"name\">run</th><th>characters</th><th>threads</th><th>median frame ms</th>"
      "<th>speedup</th><th class=\"name\">digest</th></tr>\n";
  std::map<size_t, double> first;  // per crowd size: the first run's median
  std::map<size_t, size_t> of_size;
  for (const ReportRun& run : runs) ++of_size[run.result.run.characters];
  for (const ReportRun& run : runs) {
    size_t n = run.result.run.characters;
    double median = quantile(run.result.samples.frame_ms, 0.5);
    double reference = first.emplace(n, median).first->second;
    // Alone at its crowd size (capacity's modes each at its own): nothing to compare.
    const bool alone = of_size[n] == 1;
    out += "<tr><td class=\"name\">" + html_text(run.label) + "</td><td>" + std::to_string(n) + "</td><td>" +
           std::to_string(run.result.run.threads) + "</td><td>" + report_number(median, 3) + "</td><td>" +
           (median > 0 && !alone ? report_number(reference / median, 2) + "x" : "-") + "</td><td class=\"name\">" +
           html_text(run.result.digest) + "</td></tr>\n";
  }
  return out + "</table><p>speedup: the first run of the same crowd size's median over this run's.</p>\n";
}

}  // namespace crowdprof

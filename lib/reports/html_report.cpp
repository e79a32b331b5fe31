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
#include "reports/page_files.h"
#include "reports/profile_table.h"
#include "result/result_codec.h"
#include "base/number_text.h"
#include "measuring/stats.h"

namespace crowdprof {

namespace {

std::string h(const std::string& text) {
  return xml_escape(text);
}

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

std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

// The lead of a capacity page: per mode, the largest crowd within the budget.
std::string capacity_section(const CapacityRecord& c) {
  std::string out = "<section id=\"capacity\"><h2>Capacity: the largest crowd whose median " + h(c.metric) +
                    " time fits " + report_number(c.budget_ms, 3) +
                    " ms</h2>\n<table><tr><th class=\"name\">mode</th>"
                    "<th>threads</th><th>capacity (characters)</th><th>its median ms</th><th>first over</th>"
                    "<th>its median ms</th></tr>\n";
  for (const CapacityRecord::Row& row : c.rows) {
    out += "<tr><td class=\"name\">" + h(row.mode) + "</td><td>" + std::to_string(row.threads) + "</td><td><b>" +
           (row.fit ? std::to_string(row.fit->n) : std::string("none")) + "</b></td><td>" +
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

// Labels of runs the caller did not name: the mode; with the crowd size when
// a mode comes at several sizes; with the file when even that is not enough to
// tell two results apart.
void label_runs(std::vector<ReportRun>& all) {
  std::vector<ReportRun*> runs;
  for (ReportRun& run : all)
    if (run.label.empty()) runs.push_back(&run);
  auto key = [](const ReportRun& r, int level) {
    std::string mode = r.result.run.mode;
    if (level == 0) return mode;
    std::string sized = mode + " n=" + std::to_string(r.result.run.characters);
    return level == 1 ? sized : sized + " (" + file_name(r.source) + ")";
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
  for (size_t c = 0; c < columns; ++c) out += "<th class=\"name\">" + h(alike ? "value" : runs[c].label) + "</th>";
  out += "</tr>\n";
  std::vector<std::string> keys;
  for (const auto& table : tables)
    for (const auto& row : table)
      if (std::find(keys.begin(), keys.end(), row.first) == keys.end()) keys.push_back(row.first);
  for (const std::string& key : keys) {
    out += "<tr><td class=\"name\">" + h(key) + "</td>";
    if (alike && (key == "mode" || key == "threads")) {
      // Each run's, in the runs' order, a line each (a value once).
      std::vector<std::string> values;
      for (const auto& table : tables)
        for (const auto& row : table)
          if (row.first == key && std::find(values.begin(), values.end(), row.second) == values.end())
            values.push_back(row.second);
      std::string joined;
      for (const std::string& v : values) joined += (joined.empty() ? "" : "<br>") + h(v);
      out += "<td class=\"name\">" + joined + "</td>";
    } else {
      for (size_t c = 0; c < columns; ++c) {
        std::string value;
        for (const auto& row : tables[c])
          if (row.first == key) value = row.second;
        out += "<td class=\"name\">" + h(value) + "</td>";
      }
    }
    out += "</tr>\n";
  }
  return out + "</table></section>\n";
}

// The rows of counters: a row per counter, a column per run (blank where a
// run did not record it).
std::string counter_rows(const std::vector<ReportRun>& runs, const std::vector<size_t>& rows) {
  std::string out = "<table class=\"counters\"><tr><th class=\"name\">counter (last frame)</th>";
  for (const ReportRun& run : runs) out += "<th>" + h(run.label) + "</th>";
  out += "</tr>\n";
  for (size_t i : rows) {
    out += "<tr><td class=\"name\">" + h(std::string(kCounterFields[i].name)) + "</td>";
    for (const ReportRun& run : runs)
      out += "<td>" +
             (run.result.counters.present[i] ? with_thousands(run.result.counters.values.*kCounterFields[i].member)
                                             : std::string()) +
             "</td>";
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

// Every counter the runs recorded, in the counters' own order: those some run
// counted above zero in a table, those at zero in every run folded away under
// a line that says how many.
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
  std::string out = "<section id=\"counters\"><h2>Counters (the last frame)</h2>\n";
  if (!counted.empty()) out += counter_rows(runs, counted);
  if (!zero.empty())
    out += "<details class=\"zero-counters\"><summary>" + std::to_string(zero.size()) +
           (zero.size() == 1 ? " counter was" : " counters were") + " zero in every run</summary>\n" +
           counter_rows(runs, zero) + "</details>\n";
  return out + "</section>\n";
}

// The headline a reader looks for first: per run the median frame, p95, p99
// and fps, to 3 significant digits, in µs below 1 ms.
std::string headline_section(const std::vector<ReportRun>& runs) {
  std::string out =
      "<section id=\"headline\"><table class=\"headline\"><tr><th class=\"name\">run</th>"
      "<th>median frame</th><th>p95</th><th>p99</th><th>fps (median)</th></tr>\n";
  for (const ReportRun& run : runs) {
    const std::vector<double>& ms = run.result.samples.frame_ms;
    const double median = median_frame_ms(ms);
    out += "<tr><td class=\"name\">" + h(run.label) + "</td><td class=\"key\">" + duration_text(median) + "</td><td>" +
           duration_text(quantile(ms, 0.95)) + "</td><td>" + duration_text(quantile(ms, 0.99)) + "</td><td>" +
           (median > 0 ? significant(1000.0 / median, 3) : "-") + "</td></tr>\n";
  }
  return out + "</table></section>\n";
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
  if (timed) return {report_number(median, 2), "timer queries"};
  return {"n/a", h(described.gpu_timing_missing.empty() ? "not recorded" : described.gpu_timing_missing)};
}

std::string swatch(Category category) {
  return "<span class=\"swatch\" style=\"background:" + std::string(category_colour(category)) + "\"></span>";
}

// The BGE's overlay, a column pair (ms, share) per run: for a few runs.
std::string profile_by_category(const std::vector<ReportRun>& runs, const std::vector<FrameTimes>& medians) {
  std::string out = "<table><tr><th class=\"name\">category</th>";
  for (const ReportRun& run : runs) out += "<th>" + h(run.label) + " ms</th><th>%</th>";
  out += "</tr>\n<tr><td class=\"name\"><b>Frametime</b></td>";
  for (const FrameTimes& t : medians)
    out += "<td><b>" + report_number(t.total_ms(), 2) + "</b></td><td>" +
           (t.total_ms() > 0 ? report_number(1000.0 / t.total_ms(), 1) : "-") + " fps</td>";
  out += "</tr>\n";
  for (size_t c = 0; c < kCategoryCount; ++c) {
    auto category = static_cast<Category>(c);
    out += "<tr><td class=\"name\">" + swatch(category) + h(std::string(category_name(category))) + "</td>";
    for (const FrameTimes& t : medians) {
      double share = t.total_ms() > 0 ? t.ms[c] / t.total_ms() : 0.0;
      out += "<td>" + report_number(t.ms[c], 2) + "</td><td class=\"name\">" + report_number(share * 100, 0) +
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
    out +=
        "<th>" + swatch(static_cast<Category>(c)) + h(std::string(category_name(static_cast<Category>(c)))) + "</th>";
  out += "<th>GPU time</th></tr>\n";
  for (size_t r = 0; r < runs.size(); ++r) {
    const FrameTimes& t = medians[r];
    out += "<tr><td class=\"name\">" + h(runs[r].label) + "</td><td><b>" + report_number(t.total_ms(), 2) +
           "</b></td><td>" + (t.total_ms() > 0 ? report_number(1000.0 / t.total_ms(), 1) : "-") + "</td>";
    for (size_t c : shown) out += "<td>" + report_number(t.ms[c], 2) + "</td>";
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
    out += "<tr><td class=\"name\">" + h(run.label) + "</td><td>" + std::to_string(scene.characters) + "</td><td>" +
           std::to_string(scene.joints) + "</td><td>" + std::to_string(scene.vertices) + "</td><td>" +
           std::to_string(run.result.frames()) + "</td><td>" + std::to_string(scene.warmup) +
           "</td><td class=\"name\">" + h(scene.action_choice) + "</td><td class=\"name\" title=\"" + h(scene.file) +
           "\">" + h(file_name(scene.file)) + "</td><td class=\"name\">" + h(run.result.digest) + "</td></tr>\n";
  }
  return out + "</table>\n";
}

// Runs whose profile columns fit side by side at 1280 px.
constexpr size_t kRunsSideBySide = 4;

std::string profile_section(const std::vector<ReportRun>& runs) {
  const std::vector<FrameTimes> medians = median_frames(runs);
  return "<section id=\"profile\"><h2>Profile (the BGE's table, median frame)</h2>\n" +
         (runs.size() > kRunsSideBySide ? profile_by_run(runs, medians) : profile_by_category(runs, medians)) +
         runs_table(runs) + "</section>\n";
}

// Each run's GPU time by pass (medians, and their sum against the frame's GPU
// time) with the pipeline statistics where the GL had them: only when some
// run split its GPU time.
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
    out += "<th>" + h(name) + "</th>";
  }
  out += "<th>invocations per vertex drawn</th></tr>\n";
  for (const ReportRun& run : runs) {
    const Result& r = run.result;
    if (r.samples.gpu_pass_ms[0].empty()) continue;
    const GpuPassMedians medians = gpu_pass_medians(r.samples.gpu_pass_ms, r.run.switches.passes);
    const double sum = medians.sum;
    for (size_t p = 0; p < kGpuPassCount; ++p) {
      if (!pass_drawn(static_cast<GpuPass>(p), r.run.switches.passes)) continue;
      out += "<tr><td class=\"name\">" + h(run.label) + "</td><td class=\"name\">" + std::string(kGpuPassNames[p]) +
             "</td><td>" + (medians.median[p] ? report_number(*medians.median[p], 3) : std::string("n/a")) + "</td>";
      if (r.pipeline_statistics) {
        for (size_t s = 0; s < kPipelineStatCount; ++s)
          out += "<td>" + with_thousands(static_cast<uint64_t>((*r.pipeline_statistics)[p][s])) + "</td>";
        const double reuse = r.invocations_per_vertex_drawn ? (*r.invocations_per_vertex_drawn)[p] : std::nan("");
        out += "<td>" + (std::isfinite(reuse) ? report_number(reuse, 3) : std::string("-")) + "</td>";
      } else {
        out += "<td class=\"name\" colspan=\"" + std::to_string(kPipelineStatCount + 1) + "\">unavailable: " +
               h(r.run.pipeline_statistics_missing.empty() ? "not recorded" : r.run.pipeline_statistics_missing) +
               "</td>";
      }
      out += "</tr>\n";
    }
    double gpu = metric_median(r, "gpu_ms");
    out +=
        "<tr><td class=\"name\">" + h(run.label) + "</td><td class=\"name\"><i>passes together</i></td><td>" +
        report_number(sum, 3) + "</td><td class=\"name\" colspan=\"" + std::to_string(kPipelineStatCount + 1) + "\">" +
        (gpu > 0 ? report_number(100.0 * sum / gpu, 0) + "% of the frame's GPU time (" + report_number(gpu, 3) + " ms)"
                 : std::string("the frame's GPU time is not known")) +
        "</td></tr>\n";
  }
  return out + "</table></section>\n";
}

// Each run's Animations by stage (thread ms, medians): only when some run has
// the split (results before it have none).
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
    out += "<tr><td class=\"name\">" + h(run.label) + "</td>";
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
    out += "<tr><td class=\"name\">" + h(run.label) + "</td><td>" + std::to_string(ms.size()) + "</td><td>" +
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
  for (const ReportRun& run : runs) {
    size_t n = run.result.run.characters;
    double median = quantile(run.result.samples.frame_ms, 0.5);
    double reference = first.emplace(n, median).first->second;
    out += "<tr><td class=\"name\">" + h(run.label) + "</td><td>" + std::to_string(n) + "</td><td>" +
           std::to_string(run.result.run.threads) + "</td><td>" + report_number(median, 3) + "</td><td>" +
           (median > 0 ? report_number(reference / median, 2) + "x" : "-") + "</td><td class=\"name\">" +
           h(run.result.digest) + "</td></tr>\n";
  }
  return out + "</table><p>speedup: the first run of the same crowd size's median over this run's.</p>\n";
}

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

// The A/B's verdict, the page's first section: a row per metric that says
// passed or FAILED, its change with its interval against the tolerance, then
// the work and how the builds took turns.
std::string gate_section(const GateSection& gate) {
  const GateTable& t = gate.table;
  std::string out = "<section id=\"verdict\"><h2>A/B against " + h(file_name(gate.base)) + ": " +
                    (t.failed() ? "<span class=\"regression\">FAILED</span>" : "<span class=\"ok\">passed</span>") +
                    "</h2>\n<table class=\"verdict\"><tr><th class=\"name\">metric</th><th class=\"name\">verdict</th>"
                    "<th>change</th><th>interval (" +
                    report_number(gate.confidence * 100, 0) +
                    "%)</th><th>tolerance</th><th>base</th><th>current</th><th>p (Holm)</th></tr>\n";
  for (const GateRow& row : t.metrics) {
    out += "<tr><td class=\"name\">" + h(row.metric) + "</td><td class=\"name\">" +
           (row.failed ? "<span class=\"regression\">FAILED</span>" : "<span class=\"ok\">passed</span>") + " (" +
           h(row.verdict) + ")</td><td class=\"key\">" + signed_percent(row.change, 1) + "</td><td>" +
           (row.has_interval ? "[" + signed_percent(row.change_low, 1) + ", " + signed_percent(row.change_high, 1) + "]"
                             : std::string("-")) +
           "</td><td>up to +" + report_number(gate.tolerance * 100, 1) + "%</td><td>" + report_number(row.base_ms, 3) +
           " " + h(row.unit) + "</td><td>" + report_number(row.current_ms, 3) + " " + h(row.unit) + "</td><td>" +
           (row.has_p ? html_p_text(row.p) : std::string("-")) + "</td></tr>\n";
    if (!row.why.empty()) out += "<tr><td></td><td class=\"name\" colspan=\"7\">" + h(row.why) + "</td></tr>\n";
  }
  out += "</table>\n<p>Work: " +
         std::string(!t.work_compared ? "not compared"
                     : t.work_equal   ? "the same"
                                      : "<span class=\"regression\">CHANGED</span>") +
         (t.work_detail.empty() ? std::string() : " (" + h(t.work_detail) + ")") +
         ". A change is current over base, of each group's paired medians; a metric fails when it is slower than the "
         "tolerance and the floor, and significantly so.</p>\n";
  if (!t.title.empty()) out += "<pre>" + h(t.title) + "</pre>\n";
  if (!t.reproduce.empty()) out += "<p>Reproduce: <code>" + h(t.reproduce) + "</code></p>\n";
  return out + "</section>\n";
}

// Each saving's price as a table (the scatter plot comes later): the same
// points as the cost-against-error chart, empty when it has none.
std::string cost_error_table(const std::vector<CostErrorPoint>& points) {
  if (points.empty()) return {};
  std::string out =
      "<table class=\"cost-error\"><tr><th class=\"name\">mode</th><th>median frame ms</th><th>saved ms</th>"
      "<th class=\"name\">against</th><th>largest error px</th><th>rms error px</th><th>largest error mm</th>"
      "<th class=\"name\">front</th></tr>\n";
  for (const CostErrorPoint& p : points) {
    const bool base = p.mode == p.base;
    out += "<tr><td class=\"name\">" + h(p.mode) + "</td><td>" + report_number(p.frame_ms, 3) + "</td><td>" +
           (base ? "-" : report_number(p.saved_ms, 3) + (p.saved_ms < 0 ? " (slower)" : "")) +
           "</td><td class=\"name\">" + (base ? "-" : h(p.base)) + "</td><td>" + report_number(p.error.max_px, 2) +
           "</td><td>" + report_number(p.error.rms_px, 2) + "</td><td>" + report_number(p.error.max * 1000.0, 2) +
           "</td><td class=\"name\">" +
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

// Why a calibrated verdict and the raw frame times beside it disagree: the
// calibration removes the machine's speed, the raw times keep it. Empty when
// no metric is calibrated or the page does not hold both runs.
std::string calibration_note(const CheckResult& r, const std::vector<ReportRun>& runs) {
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
         duration_text(base) + " in the baseline, " + duration_text(current) + " now (" +
         signed_percent(base > 0 ? current / base - 1 : NAN, 1) +
         "); what of that the calibrated change does not show is the machine's drift between the two runs, not "
         "the code.</p>\n";
}

std::string check_section(const CheckSection& check, const std::vector<ReportRun>& runs, std::string& charts) {
  const CheckResult& r = check.result;
  std::string verdict = r.regressed() ? "<span class=\"regression\">REGRESSION</span>" : "<span class=\"ok\">ok</span>";
  std::string out = "<section id=\"check\"><h2>" +
                    std::string(check.command == "diff" ? "Diff against " : "Check against ") + h(check.baseline) +
                    ": " + verdict + "</h2>\n";
  out +=
      "<table class=\"verdict\"><tr><th class=\"name\">metric</th><th>baseline median</th><th>current "
      "median</th><th>change</th>"
      "<th>p (Mann-Whitney U, Holm)</th><th>floor</th><th class=\"name\">verdict</th></tr>\n";
  VerdictChart rows = verdict_chart(r, check.options);
  for (size_t m = 0; m < r.metrics.size(); ++m) {
    const MetricCheck& metric = r.metrics[m];
    // Milliseconds, or "probes" for the calibrated frame (a ratio).
    const std::string unit = " " + metric.value_unit;
    out += "<tr><td class=\"name\">" + h(metric.metric) + "</td><td>" +
           metric_value_text(metric, metric.baseline.median) + unit + "</td><td>" +
           metric_value_text(metric, metric.current.median) + unit + "</td><td>" +
           (std::isfinite(metric.change) ? (metric.change >= 0 ? "+" : "") + report_number(metric.change * 100, 1) + "%"
                                         : "n/a") +
           "</td><td>" + (metric.tested ? html_p_text(metric.p_adjusted) : "-") + "</td><td>" +
           metric_value_text(metric, metric.floor_ms) + unit + "</td><td class=\"name\">" + h(rows.rows[m].verdict) +
           "</td></tr>\n";
  }
  out += "</table>\n<p>Tolerance " + report_number(check.options.tolerance * 100, 1) +
         "% and the floor (a slowdown must pass both; the green band is the larger), "
         "significance level " +
         report_number(check.options.alpha, 3) + " after Holm's correction over the metrics.</p>\n" +
         calibration_note(r, runs);
  SvgDocument svg;
  svg.add(rows);
  charts += "v";
  out += svg.inline_svg() + "<p>";
  const bool digests_equal = r.baseline_digest == r.current_digest;
  if (r.counters.empty() && r.counters_missing.empty() && digests_equal)
    out += "Counters and digest match the baseline.";
  else if (r.counters.empty() && r.counters_missing.empty() && !r.digest_differs())
    out += "Counters match the baseline; digest " + h(r.digest_note()) + ".";
  for (const CounterDifference& d : r.counters)
    out += "<span class=\"regression\">Counter " + h(d.name) + " changed: " + std::to_string(d.baseline) + " &#8594; " +
           std::to_string(d.current) + " per frame.</span><br>";
  for (const std::string& name : r.counters_missing)
    out += "<span class=\"regression\">Counter " + h(name) + " is in the baseline, missing here.</span><br>";
  if (r.digest_differs())
    out += "<span class=\"regression\">Digest changed: " + h(r.baseline_digest) + " &#8594; " + h(r.current_digest) +
           "</span>";
  else if (r.digest_not_comparable() && !(r.counters.empty() && r.counters_missing.empty()))
    out += "Digest " + h(r.digest_note()) + ".";
  return out + "</p></section>\n";
}

}  // namespace

void require_png(const std::string& bytes, const std::string& path) {
  static const std::string kSignature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.size() < 33 || bytes.compare(0, 8, kSignature) != 0 || bytes.compare(12, 4, "IHDR") != 0)
    throw InputError(path, "not a PNG image");
}

void add_document(HtmlReportInput& input, ResultDocument document, const std::string& source) {
  for (Result& run : document.runs) input.runs.push_back({"", std::move(run), source});
  if (document.kind == "bench") return;
  input.sweep_axis = document.sweep_axis;
  for (const ModeMedians& m : document.sweep) input.sweep.push_back({m.mode, m.on(document.sweep_axis), m.frame_ms});
  if (document.capacity && document.capacity->metric == "frame" && document.capacity->budget_ms > 0)
    input.sweep_budget_ms = document.capacity->budget_ms;
  if (document.capacity) input.capacity = std::move(document.capacity);
}

void add_result(HtmlReportInput& input, Result result, const std::string& source) {
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
    from += (s ? ", " : " of ") + file_name(input.sources[s]);
  if (input.sources.size() > 2) from += " and " + std::to_string(input.sources.size() - 2) + " more";
  std::string title = "crowdprof report" + from + ": " + caption +
                      (input.capacity ? ", capacity within " + report_number(input.capacity->budget_ms, 3) + " ms of " +
                                            input.capacity->metric
                       : input.gate ? ", A/B check against " + file_name(input.gate->base) + ": " +
                                          (input.gate->table.failed() ? "FAILED" : "passed")
                       : input.check            ? ", " + input.check->command
                       : !input.command.empty() ? ", " + input.command
                       : input.runs.size() > 1  ? ", " + std::to_string(input.runs.size()) + " runs"
                                                : ", " + input.runs.front().label);
  std::string charts;  // one letter per chart, for the count the page checks
  std::string body;
  body += "<h1>" + h(title) + "</h1>\n<p class=\"sources\">";
  if (!input.sources.empty()) {
    body += "From ";
    for (size_t s = 0; s < input.sources.size(); ++s) body += (s ? ", " : "") + h(input.sources[s]);
    body += ". ";
  }
  body += "Made by crowdprof " + h(first.environment.version) + "; one file, no network needed.</p>\n";
  // The answer first: the verdict, the capacities, the headline and, for
  // several runs, the speedups and each saving's price; the charts after.
  if (input.gate) body += gate_section(*input.gate);
  if (input.capacity) body += capacity_section(*input.capacity);
  if (input.check) body += check_section(*input.check, input.runs, charts);
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
         h(title) + "</title>\n<script>\n" + std::string(page_file("lib/reports/page/error_hook.js")) +
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

#include "reports/profile_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "measuring/stats.h"
#include "base/number_text.h"
#include "result/result_codec.h"
#include "reports/text_table.h"

namespace crowdprof {

namespace {

std::vector<double> frame_ms(const std::vector<FrameRecord>& frames) {
  std::vector<double> out;
  for (const FrameRecord& f : frames) out.push_back(f.times.total_ms());
  return out;
}

// The frames' GPU times that were measured (NaN: not).
std::vector<double> gpu_ms(const std::vector<FrameRecord>& frames) {
  std::vector<double> out;
  for (const FrameRecord& f : frames)
    if (std::isfinite(f.gpu_ms)) out.push_back(f.gpu_ms);
  return out;
}

// A median GPU time the timer cannot tell from nothing (render/gpu_timer.h).
bool below_timer_resolution(double median_ms, const RunDescription& run) {
  return run.gpu_timer_resolution_ms > 0 && median_ms < run.gpu_timer_resolution_ms;
}

// "0.00125": a small number with its 3 significant digits.
std::string significant(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

// "8.93ms", or below 0.01 ms "4.2us": a small time never reads 0.00.
std::string short_time(double ms) {
  char text[32];
  if (ms >= 0.01)
    std::snprintf(text, sizeof text, "%.2fms", ms);
  else
    std::snprintf(text, sizeof text, "%.3gus", ms * 1000.0);
  return text;
}

// The frame's GPU time by pass (median of the frames split), the passes'
// sum against the median GPU time, each pass's pipeline statistics and its
// vertex reuse, as the result recorded them.
std::string format_gpu_passes(const Result& report, const std::vector<double>& gpu) {
  const RunDescription& run = report.run;
  if (report.samples.gpu_pass_ms[0].empty()) return {};
  const uint32_t passes = run.switches.passes;
  std::string out = "GPU passes : ";
  const GpuPassMedians medians = gpu_pass_medians(report.samples.gpu_pass_ms, passes);
  const double sum = medians.sum;
  for (size_t p = 0; p < kGpuPassCount; ++p) {
    if (!pass_drawn(static_cast<GpuPass>(p), passes)) continue;
    out += std::string(p == 0 ? "" : " | ") + std::string(kGpuPassNames[p]) + " " +
           (medians.median[p] ? short_time(*medians.median[p]) : std::string("n/a"));
  }
  double gpu_median = gpu.empty() ? 0 : summarize(gpu).median;
  if (gpu_median > 0 && !below_timer_resolution(gpu_median, run))
    out += "   medians; together " + fixed(100.0 * sum / gpu_median, 0) + "% of the GPU time";
  else
    out += "   medians; the GPU time is below the timer's resolution: not a measurement";
  out += "\n";
  if (!report.pipeline_statistics) {
    const std::string why =
        run.pipeline_statistics_missing.empty() ? std::string("not read back") : run.pipeline_statistics_missing;
    return out + "Pipeline statistics: unavailable (" + why + ")\nVertex reuse: not counted (" + why + ")\n";
  }
  std::vector<std::vector<std::string>> rows = {{"per frame (median)"}};
  for (size_t p = 0; p < kGpuPassCount; ++p)
    if (pass_drawn(static_cast<GpuPass>(p), passes)) rows[0].emplace_back(kGpuPassNames[p]);
  for (size_t s = 0; s < kPipelineStatCount; ++s) {
    std::string name(kPipelineStatNames[s]);
    std::replace(name.begin(), name.end(), '_', ' ');
    rows.push_back({name});
    for (size_t p = 0; p < kGpuPassCount; ++p)
      if (pass_drawn(static_cast<GpuPass>(p), passes))
        rows.back().push_back(with_thousands(static_cast<uint64_t>((*report.pipeline_statistics)[p][s])));
  }
  if (report.invocations_per_vertex_drawn) {
    rows.push_back({"invocations per vertex drawn"});
    for (size_t p = 0; p < kGpuPassCount; ++p) {
      if (!pass_drawn(static_cast<GpuPass>(p), passes)) continue;
      const double reuse = (*report.invocations_per_vertex_drawn)[p];
      rows.back().push_back(std::isfinite(reuse) ? fixed(reuse, 3) : std::string("-"));
    }
  }
  return out + "Pipeline statistics (ARB_pipeline_statistics_query; index order " +
         std::string(to_string(run.switches.index_order)) + "):\n" + align_columns(rows, {0});
}

}  // namespace

std::string format_drawn_error(const DrawnErrorRecord& e) {
  std::ostringstream out;
  out << "drawn error against exact full-detail poses: max " << fixed(e.max * 1000.0, 2) << " mm ("
      << fixed(e.max_fraction * 100.0, 3) << "% of height, " << fixed(e.max_px, 2) << " px), RMS "
      << fixed(e.rms * 1000.0, 2) << " mm (" << fixed(e.rms_px, 2) << " px) over " << e.copies_checked
      << " copies on screen" << (e.copy_stride > 1 ? " (one in " + std::to_string(e.copy_stride) + ")" : "") << ", "
      << e.copies_deviating << " drawn inexactly";
  if (e.mesh_max > 0) out << ", mesh levels up to " << fixed(e.mesh_max * 1000.0, 2) << " mm of it";
  out << "; " << fixed(e.switches_per_second, 1) << " rate switches/s\n";
  return out.str();
}

std::string format_culling_audit(const CullingAudit& c) {
  std::ostringstream out;
  out << "culling audit (" << c.frames << " exact pose" << (c.frames == 1 ? "" : "s") << " of " << c.copies << " copies"
      << (c.copy_stride > 1 ? " (one in " + std::to_string(c.copy_stride) + ")" : std::string()) << " in "
      << fixed(c.ms, 0) << " ms; " << c.in_view << " in view, " << c.outside << " outside"
      << (c.undecided ? ", " + std::to_string(c.undecided) + " undecided" : "") << "):";
  for (size_t b = 0; b < c.boxes.size(); ++b) {
    const CullBoxAudit& box = c.boxes[b];
    std::string name(cull_box_name(static_cast<CullBox>(b)));
    std::replace(name.begin(), name.end(), '_', '-');
    out << (b ? " |" : "") << " " << name << (static_cast<CullBox>(b) == CullBox::EveryAction ? " (this run's)" : "")
        << " " << box.false_culls << " false culls, " << box.missed_culls
        << " missed, slack "
        // None measured where every exact box is flat (no volume to compare).
        << (box.slack_mean > 0 ? fixed(box.slack_mean, 2) + "x" : std::string("n/a (flat)"));
  }
  out << "\n";
  return out.str();
}

std::string format_profile(const Result& report) {
  std::ostringstream out;
  const RunDescription& run = report.run;
  if (report.frame_records.empty())
    return report.partial ? "no frames measured: interrupted during the warm-up\n" : "no frames measured\n";
  const FrameRecord& frame = report.frame_records[median_frame(report.frame_records)];
  double total = frame.times.total_ms();
  char line[160];
  std::snprintf(line, sizeof line, "Frametime : %8.2fms (%.1ffps)   median of %zu frames\n", total,
                total > 0 ? 1000.0 / total : 0.0, report.frame_records.size());
  out << line;
  for (size_t c = 0; c < kCategoryCount; ++c) {
    double ms = frame.times.ms[c];
    double share = total > 0 ? ms / total : 0.0;
    std::string name(category_name(static_cast<Category>(c)));
    std::string bar(static_cast<size_t>(share * 40.0 + 0.5), '|');
    std::snprintf(line, sizeof line, "%-11s: %8.2fms | %3.0f%%%s%s\n", name.c_str(), ms, share * 100.0,
                  bar.empty() ? "" : " ", bar.c_str());  // no trailing blank for diff-friendly output
    out << line;
  }
  // The GPU's own time, from timer queries: beside the categories, not one of
  // them (GPU Latency stays the CPU's wait in finish). Never a made-up zero.
  std::vector<double> gpu = gpu_ms(report.frame_records);
  if (!gpu.empty() && below_timer_resolution(summarize(gpu).median, run))
    std::snprintf(line, sizeof line, "%-11s: %8s     below the timer's resolution (%s ms): not a measurement\n",
                  "GPU time", "-", significant(run.gpu_timer_resolution_ms).c_str());
  else if (!gpu.empty())
    std::snprintf(line, sizeof line, "%-11s: %10s   median of %zu frames, GL timer queries (beside the frame)\n",
                  "GPU time", short_time(summarize(gpu).median).c_str(), gpu.size());
  else
    std::snprintf(
        line, sizeof line, "%-11s: %8s     %s\n", "GPU time", "n/a",
        (run.gpu_timing_missing.empty() ? std::string("no timer query was read back") : run.gpu_timing_missing)
            .c_str());
  out << line;
  out << format_gpu_passes(report, gpu);
  // The slow frames, which a median hides: a game stutters on its p99.
  std::vector<double> totals = frame_ms(report.frame_records);
  Summary s = summarize(totals);
  // (The median is Frametime's, above: one median per run.)
  std::snprintf(line, sizeof line, "Slow frames: p95 %.2f | p99 %.2f | max %.2f ms\n", s.p95, s.p99, s.max);
  out << line;
  if (std::optional<AnimationSplit> split = animation_split(report)) {
    out << "Animations by stage:";
    for (size_t st = 0; st < kAnimationStageCount; ++st)
      out << (st ? " |" : "") << " " << kAnimationStageLabels[st] << " " << fixed(split->median_ms[st], 3);
    out << " ms of thread time (medians";
    if (split->threads > 1) out << ", " << split->threads << " threads";
    out << "; " << fixed(100.0 * split->coverage, 0) << "% of Animations'" << (split->threads > 1 ? " thread time" : "")
        << ")\n";
  }
  // The counters the JSON and the page record: each the median over frames.
  const Counters& k = report.counters.values;
  if (run.crowd.size() > 1)
    out << run.characters << " characters of " << run.crowd.size() << " kinds (up to " << run.joints << " joints, "
        << run.vertices << " vertices) | mode ";
  else
    out << run.characters << " characters x " << run.joints << " joints, " << run.vertices << " vertices | mode ";
  out << run.mode << " | " << run.threads << (run.threads == 1 ? " thread" : " threads") << " | backend " << run.backend
      << " | " << k.copies_culled << " copies culled, " << k.copies_visible << " on screen | " << k.poses_updated
      << " poses, " << k.vertices_skinned << " vertices skinned, " << k.channel_lookups << " lookups";
  // Transitions from the switch, or from a scene file's groups (seen in their counters).
  if (run.switches.transitions_s > 0 || k.fades > 0 || k.actions_sampled != k.poses_updated)
    out << ", " << k.actions_sampled << " actions sampled, " << k.fades << " fades, "
        << (k.layers > 0 ? std::to_string(k.layers) + " layers, " : "") << k.joints_blended << " joints blended";
  out << " per frame\n";
  if (run.backend != "none" || k.copies_fallback > 0) {
    out << "renderer " << run.renderer << " | " << k.draw_calls << " draw calls, " << k.bytes_uploaded
        << " bytes uploaded per frame";
    // GPU skinning's share of them (issue 52): palettes and per-copy records.
    if (k.palette_bytes_uploaded > 0 || k.record_bytes_uploaded > 0)
      out << " (palettes " << k.palette_bytes_uploaded << ", records " << k.record_bytes_uploaded << ")";
    if (k.gpu_palette_bytes > 0) out << " | " << k.gpu_palette_bytes << " bytes of palettes on the GPU";
    if (k.copies_fallback > 0)
      out << " | " << k.copies_fallback << " copies skinned on the CPU: over the GPU's bone limit";
    out << "\n";
  }
  if (run.gpu_memory) {
    const GpuMemoryRecord& m = *run.gpu_memory;
    auto mib = [](uint64_t bytes) { return with_thousands(bytes >> 20) + " MiB"; };
    out << "GPU memory ";
    if (m.total_bytes) out << mib(*m.total_bytes) << (m.free_bytes ? ", " : "");
    if (m.free_bytes) out << mib(*m.free_bytes) << " free";
    if (!m.total_bytes && !m.free_bytes)
      out << "unknown (the GL has neither NVX_gpu_memory_info nor ATI_meminfo)";
    else
      out << " (" << m.source << ")";
    out << " | largest storage block " << mib(m.max_storage_block_bytes) << "\n";
  }
  if (run.gpu_skinning) {
    const GpuSkinningRecord& g = *run.gpu_skinning;
    out << "skinning " << g.skinning << " | " << g.gpu_bytes << " bytes on the GPU";
    if (g.bake) {
      std::snprintf(line, sizeof line,
                    " | baked at %g Hz (%llu samples) in %.1f ms | largest vertex deviation from exact sampling %.3g "
                    "model units, %.3f%% of the character's height",
                    g.bake->rate_hz, static_cast<unsigned long long>(g.bake->samples), g.bake->bake_ms,
                    g.bake->max_deviation, 100.0 * g.bake->max_deviation_fraction);
      out << line;
    }
    out << "\n";
  }
  if (run.crowd.size() > 1) {
    // As wide as the longest name, up to 48 (a generated character's gen command); longer ones keep their end.
    int width = 28;
    for (const CharacterRun& c : run.crowd)
      width = std::max(width, static_cast<int>(std::min<size_t>(c.file.size(), 48)));
    const auto w = static_cast<size_t>(width);
    // Each kind's counters are its last frame's (the run keeps no per-kind
    // frames): with changing work they need not add up to the medians above.
    out << "by character, the last frame:\n";
    std::snprintf(line, sizeof line, "%-*s %6s %6s %8s %9s %6s %6s %16s %9s\n", width, "file", "copies", "joints",
                  "vertices", "on screen", "culled", "poses", "vertices skinned", "fallbacks");
    out << line;
    for (const CharacterRun& c : run.crowd) {
      const Counters& n = c.counters;
      std::string label = c.file.size() > w ? "..." + c.file.substr(c.file.size() - (w - 3)) : c.file;
      std::snprintf(line, sizeof line, "%-*s %6zu %6zu %8zu %9llu %6llu %6llu %16llu %9llu\n", width, label.c_str(),
                    c.copies, c.joints, c.vertices, static_cast<unsigned long long>(n.copies_visible),
                    static_cast<unsigned long long>(n.copies_culled), static_cast<unsigned long long>(n.poses_updated),
                    static_cast<unsigned long long>(n.vertices_skinned),
                    static_cast<unsigned long long>(n.copies_fallback));
      out << line;
    }
  }
  out << "actions " << run.action_choice;
  if (run.action_choice == "scene") {
    out << " file (";
    for (size_t c = 0; c < run.crowd.size(); ++c) out << (c ? ", " : "") << run.crowd[c].action_choice;
    out << ", seed " << run.seed << ")";
  }
  if (run.action_choice == "random")
    out << " (seed " << run.seed << ")";
  else if (!run.action.empty())
    out << " (" << run.action << ")";
  out << " | " << report.frame_records.size() << " frames after " << run.warmup << " warm-up at " << fixed(run.fps, 0)
      << " fps simulated | digest " << report.digest << "\n";
  if (report.animation) {
    const AnimationRecord& a = *report.animation;
    out << "animation: " << k.poses_updated << " poses evaluated for " << k.copies_updated << " copies updated, "
        << k.copies_held << " held | rates (copies every 1/2/4/8/16/32/64 frames):";
    for (uint64_t count : a.copies_by_rate) out << " " << count;
    out << " | longest gap " << a.longest_gap_frames << " frames | deviation " << fixed(a.max_deviation, 4) << " ("
        << fixed(a.deviation_fraction_of_height * 100.0, 2) << "% of height) over " << a.copies_checked
        << " copies on screen\n";
  }
  if (report.mesh_lod) {
    const MeshLodRecord& m = *report.mesh_lod;
    out << "mesh LOD: copies on screen by level (0: full mesh)";
    for (size_t l = 0; l < m.levels.size(); ++l) out << (l ? " / " : " ") << m.levels[l].copies;
    out << (m.levels.size() > 1 ? " | error by level" : " | no coarser level: info says why");
    for (size_t l = 1; l < m.levels.size(); ++l) {
      const MeshLevelRecord& level = m.levels[l];
      out << (l > 1 ? " / " : " ") << fixed(level.error * 1000.0, 2) << " mm ("
          << fixed(level.error_fraction * 100.0, 2) << "% of height"
          << (level.copies ? ", " + fixed(level.error_px, 2) + " px" : std::string()) << ")";
    }
    out << "\n";
  }
  if (report.drawn_error) out << format_drawn_error(*report.drawn_error);
  if (report.culling_audit) out << format_culling_audit(*report.culling_audit);
  if (report.partial)
    out << "partial: interrupted after " << report.frame_records.size() << " of " << report.frames_planned
        << " frames; the figures above are of those\n";
  return out.str();
}

std::string csv_header() {
  std::string header = "frame,mode,characters,threads,frame_ms";
  for (size_t c = 0; c < kCategoryCount; ++c) {
    header += ',';
    header += category_column(static_cast<Category>(c));
    header += "_ms";
  }
  for (size_t i = 0; i < kCsvCountersBeforeGpu; ++i) {
    header += ',';
    header += kCounterFields[i].name;
  }
  // Appended after the counters, as columns never move: GL timer queries, n/a
  // when not measured; then the CPU time of every thread in the frame (check's
  // default metric).
  header += ",gpu_ms,cpu_ms";
  // Then Animations by stage, thread ms (measuring/animation_stages.h).
  for (size_t st = 0; st < kAnimationStageCount; ++st) header += "," + animation_stage_series(st);
  // Counters added since: after everything else, as columns never move.
  for (size_t i = kCsvCountersBeforeGpu; i < kCounterFields.size(); ++i) {
    header += ',';
    header += kCounterFields[i].name;
  }
  return header;
}

void write_csv(const Result& report, std::ostream& out) {
  out << csv_header() << "\n";
  for (size_t i = 0; i < report.frame_records.size(); ++i) {
    const FrameRecord& f = report.frame_records[i];
    out << i << "," << report.run.mode << "," << report.run.characters << "," << report.run.threads << ","
        << fixed(f.times.total_ms(), 4);
    for (double ms : f.times.ms) out << "," << fixed(ms, 4);
    for (size_t c = 0; c < kCsvCountersBeforeGpu; ++c) out << "," << f.counters.*kCounterFields[c].member;
    out << "," << (std::isfinite(f.gpu_ms) ? fixed(f.gpu_ms, 4) : std::string("n/a")) << "," << fixed(f.cpu_ms, 4);
    for (double ms : f.animation_stages.ms) out << "," << fixed(ms, 4);
    for (size_t c = kCsvCountersBeforeGpu; c < kCounterFields.size(); ++c)
      out << "," << f.counters.*kCounterFields[c].member;
    out << "\n";
  }
}

}  // namespace crowdprof

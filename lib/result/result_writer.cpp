#include "result/result_codec.h"

#include <cmath>

#include "base/switch_table.h"
#include "result/result_keys.h"
#include "measuring/stats.h"

namespace crowdprof {

namespace {

using nlohmann::json;
using result_keys::counter_field;
using result_keys::kCharacterCounters;
using result_keys::pass_samples_key;

json summary_json(const std::vector<double>& values) {
  Summary s = summarize(values);
  return {{"min_ms", s.min}, {"median_ms", s.median}, {"mean_ms", s.mean}, {"p50_ms", s.median},
          {"p95_ms", s.p95}, {"p99_ms", s.p99},       {"max_ms", s.max},   {"stddev_ms", s.stddev}};
}

json lens_json(const std::optional<LensRecord>& lens) {
  if (!lens) return nullptr;
  return {{"focal_mm", lens->focal_mm},
          {"sensor_width_mm", lens->sensor_width_mm},
          {"sensor_height_mm", lens->sensor_height_mm},
          {"sensor_fit", lens->sensor_fit}};
}

json gpu_skinning_json(const GpuSkinningRecord& g) {
  json j = {{"skinning", g.skinning}, {"gpu_bytes", g.gpu_bytes}};
  if (g.bake) {
    j["rate_hz"] = g.bake->rate_hz;
    j["samples"] = g.bake->samples;
    j["bake_ms"] = g.bake->bake_ms;
    j["max_deviation"] = g.bake->max_deviation;
    j["max_deviation_fraction"] = g.bake->max_deviation_fraction;
  }
  return j;
}

json animation_json(const AnimationRecord& a) {
  return {{"copies_by_rate", a.copies_by_rate},
          {"longest_gap_frames", a.longest_gap_frames},
          {"budget_demotions", a.budget_demotions},
          {"max_deviation", a.max_deviation},
          {"deviation_fraction_of_height", a.deviation_fraction_of_height},
          {"copies_checked", a.copies_checked},
          {"copies_deviating", a.copies_deviating}};
}

json mesh_lod_json(const MeshLodRecord& m) {
  json copies = json::array(), error = json::array(), fraction = json::array(), px = json::array();
  for (const MeshLevelRecord& l : m.levels) {
    copies.push_back(l.copies);
    error.push_back(l.error);
    fraction.push_back(l.error_fraction);
    px.push_back(l.error_px);
  }
  return {{"copies", copies}, {"error", error}, {"error_fraction", fraction}, {"error_px", px}};
}

json drawn_error_json(const DrawnErrorRecord& e) {
  return {{"copies_checked", e.copies_checked},
          {"copies_deviating", e.copies_deviating},
          {"vertices", e.vertices},
          {"copy_stride", e.copy_stride},
          {"max", e.max},
          {"rms", e.rms},
          {"max_fraction", e.max_fraction},
          {"rms_fraction", e.rms_fraction},
          {"max_px", e.max_px},
          {"rms_px", e.rms_px},
          {"mesh_max", e.mesh_max},
          {"switches_per_second", e.switches_per_second}};
}

json culling_audit_json(const CullingAudit& c) {
  json boxes = json::object();
  for (size_t k = 0; k < kCullBoxes; ++k) {
    const CullBoxAudit& b = c.boxes[k];
    boxes[std::string(cull_box_name(static_cast<CullBox>(k)))] = {
        {"drawn", b.drawn},
        {"false_culls", b.false_culls},
        {"missed_culls", b.missed_culls},
        {"worst_frame_false_culls", b.worst_frame_false_culls},
        {"worst_frame_missed_culls", b.worst_frame_missed_culls},
        {"slack_mean", b.slack_mean},
        {"slack_max", b.slack_max}};
  }
  return {{"frames", c.frames},
          {"copies", c.copies},
          {"copy_stride", c.copy_stride},
          {"in_view", c.in_view},
          {"outside", c.outside},
          {"undecided", c.undecided},
          {"boxes", boxes},
          {"ms", c.ms}};
}

json instructions_json(const InstructionRecord& i) {
  json j = {{"source", i.source}, {"threads", i.threads}, {"simd", i.simd}, {"compiler", i.compiler}};
  j["per_frame"] = i.per_frame ? json(*i.per_frame) : json(nullptr);
  if (!i.problem.empty()) j["problem"] = i.problem;
  if (!i.runs.empty()) j["runs"] = i.runs;
  if (i.frames > 0) {
    j["frames"] = i.frames;
    j["warmup"] = i.warmup;
  }
  return j;
}

json crowd_json(const std::vector<CharacterRun>& crowd) {
  json out = json::array();
  for (const CharacterRun& c : crowd) {
    json counters = json::object();
    for (std::string_view name : kCharacterCounters)
      counters[std::string(name)] = c.counters.*counter_field(name)->member;
    out.push_back({{"file", c.file},
                   {"character", c.character},
                   {"copies", c.copies},
                   {"joints", c.joints},
                   {"vertices", c.vertices},
                   {"actions", c.actions},
                   {"action_choice", c.action_choice},
                   {"counters", counters}});
    if (!c.content_hash.empty()) out.back()["asset_hash"] = c.content_hash;
  }
  return out;
}

// gpu_time.passes (each pass drawn: its median, and pipeline statistics when
// read), the passes' coverage of the GPU time, and samples.gpu_<pass>_ms.
void write_gpu_passes(const Result& r, double gpu_median, json& gpu_time, json& samples) {
  json passes = json::array();
  const GpuPassMedians medians = gpu_pass_medians(r.samples.gpu_pass_ms, r.run.switches.passes);
  for (size_t p = 0; p < kGpuPassCount; ++p) {
    if (!pass_drawn(static_cast<GpuPass>(p), r.run.switches.passes)) continue;
    json pass = {{"pass", kGpuPassNames[p]},
                 {"median_ms", medians.median[p] ? json(*medians.median[p]) : json(nullptr)}};
    if (r.pipeline_statistics) {
      json statistics = json::object();
      for (size_t s = 0; s < kPipelineStatCount; ++s)
        statistics[std::string(kPipelineStatNames[s])] = std::llround((*r.pipeline_statistics)[p][s]);
      pass["statistics"] = statistics;
    }
    if (r.invocations_per_vertex_drawn && std::isfinite((*r.invocations_per_vertex_drawn)[p]))
      pass["invocations_per_vertex_drawn"] = (*r.invocations_per_vertex_drawn)[p];
    passes.push_back(pass);
    json per_frame = json::array();
    for (double v : r.samples.gpu_pass_ms[p]) per_frame.push_back(std::isfinite(v) ? json(v) : json(nullptr));
    samples[pass_samples_key(p)] = per_frame;
  }
  gpu_time["passes"] = passes;
  gpu_time["pass_coverage"] = gpu_median > 0 ? json(medians.sum / gpu_median) : json(nullptr);
  if (!r.pipeline_statistics)
    gpu_time["statistics_reason"] =
        r.run.pipeline_statistics_missing.empty() ? "not read back" : r.run.pipeline_statistics_missing;
}

// "gpu_time" and samples.gpu_ms: numbers only where a GPU timer measured, never
// made-up zeros.
void write_gpu_time(const Result& r, json& j, json& samples) {
  std::vector<double> gpu = finite(r.samples.gpu_ms);
  json gpu_time = {{"available", !gpu.empty()}};
  if (gpu.empty()) {
    gpu_time["reason"] = r.run.gpu_timing_missing.empty() ? "no timer query was read back" : r.run.gpu_timing_missing;
    gpu_time["median_ms"] = nullptr;
    samples["gpu_ms"] = nullptr;
  } else {
    double median = summarize(gpu).median;
    gpu_time["source"] = "GL_TIME_ELAPSED timer queries";
    gpu_time.update(summary_json(gpu));
    if (r.run.gpu_timer_resolution_ms > 0) gpu_time["resolution_ms"] = r.run.gpu_timer_resolution_ms;
    gpu_time["below_resolution"] = r.run.gpu_timer_resolution_ms > 0 && median < r.run.gpu_timer_resolution_ms;
    json per_frame = json::array();
    for (double ms : r.samples.gpu_ms) per_frame.push_back(std::isfinite(ms) ? json(ms) : json(nullptr));
    samples["gpu_ms"] = per_frame;
    if (!r.samples.gpu_pass_ms[0].empty()) write_gpu_passes(r, median, gpu_time, samples);
  }
  j["gpu_time"] = gpu_time;
}

}  // namespace

nlohmann::json environment_to_json(const Result& r) {
  const Environment& env = r.environment;
  return {{"cpu", env.cpu},           {"cores", env.cores},
          {"compiler", env.compiler}, {"build_type", env.build_type},
          {"simd", env.simd},         {"fused_multiply_add", env.fused_multiply_add},
          {"backend", r.run.backend}, {"renderer", r.run.renderer}};
}

nlohmann::json result_to_json(const Result& r) {
  const RunDescription& run = r.run;
  const Environment& env = r.environment;
  json j;
  j["crowdprof"] = {{"version", env.version}, {"commit", env.commit}, {"format", kResultFormat}};
  j["environment"] = environment_to_json(r);
  j["scene"] = {{"file", run.file},
                {"character", run.character},
                {"characters", run.characters},
                {"joints", run.joints},
                {"vertices", run.vertices},
                {"actions", run.actions},
                {"action_choice", run.action_choice},
                {"action", run.action},
                {"seed", run.seed},
                {"camera", run.camera},
                {"resolution", run.resolution}};
  j["scene"]["lens"] = lens_json(run.lens);
  if (!run.scene_file.empty()) {
    j["scene"]["scene_file"] = run.scene_file;
    j["scene"]["scene_hash"] = run.scene_hash;
  }
  if (r.file_from_result) j["scene"]["file_from"] = "result";
  j["crowd"] = crowd_json(run.crowd);
  j["mode"] = run.mode;
  j["switches"] = switches_to_json(run.switches);
  if (run.gpu_skinning) j["gpu_skinning"] = gpu_skinning_json(*run.gpu_skinning);
  if (run.gpu_memory) {
    const GpuMemoryRecord& m = *run.gpu_memory;
    json memory = {{"source", m.source}, {"max_storage_block_bytes", m.max_storage_block_bytes}};
    memory["total_bytes"] = m.total_bytes ? json(*m.total_bytes) : json(nullptr);
    memory["free_bytes"] = m.free_bytes ? json(*m.free_bytes) : json(nullptr);
    j["gpu_memory"] = memory;
  }
  j["threads"] = run.threads;
  j["frames"] = r.frames();
  j["warmup"] = run.warmup;
  j["fps"] = run.fps;
  const ResultSamples& s = r.samples;
  j["frame"] = summary_json(s.frame_ms);
  json samples = {{"frame_ms", s.frame_ms}};
  if (!s.cpu_ms.empty()) {
    j["cpu"] = summary_json(s.cpu_ms);
    samples["cpu_ms"] = s.cpu_ms;
  }
  if (!s.probe_ms.empty()) {
    // The ratio has no unit: its median alone, not a summary of "_ms" fields.
    j["calibration"] = {{"probe", r.calibration_probe},
                        {"probe_ms", summary_json(s.probe_ms)},
                        {"median_calibrated", summarize(finite(s.calibrated)).median}};
    samples["probe_ms"] = s.probe_ms;
    samples["calibrated"] = s.calibrated;
  }
  for (size_t c = 0; c < kCategoryCount; ++c) {
    const std::string name = series_name(static_cast<Category>(c));
    j["categories"][name] = summary_json(s.category_ms[c]);
    samples[name] = s.category_ms[c];
  }
  if (std::optional<AnimationSplit> split = animation_split(r)) {
    json stages = json::object();
    for (size_t st = 0; st < kAnimationStageCount; ++st) {
      stages[std::string(kAnimationStageNames[st])] = summary_json(s.animation_stage_ms[st]);
      stages[std::string(kAnimationStageNames[st])]["share"] = split->share[st];
      samples[animation_stage_series(st)] = s.animation_stage_ms[st];
    }
    j["animations_split"] = {
        {"unit", "thread ms"}, {"threads", split->threads}, {"coverage", split->coverage}, {"stages", stages}};
  }
  write_gpu_time(r, j, samples);
  j["counters"] = json::object();
  for (size_t i = 0; i < kCounterFields.size(); ++i)
    if (r.counters.present[i])
      j["counters"][std::string(kCounterFields[i].name)] = r.counters.values.*kCounterFields[i].member;
  j["digest"] = r.digest;
  j["digest_cpu_vertices"] = r.digest_cpu_vertices;
  j["vertex_order"] = r.vertex_order;
  j["digest_scheme"] = r.digest_scheme;
  if (!r.stores.empty()) j["stores"] = r.stores;
  if (r.bytes_uploaded_per_copy_on_screen)
    j["bytes_uploaded_per_copy_on_screen"] = *r.bytes_uploaded_per_copy_on_screen;
  if (r.palette_bytes_per_copy_on_screen) j["palette_bytes_per_copy_on_screen"] = *r.palette_bytes_per_copy_on_screen;
  if (r.record_bytes_per_copy_on_screen) j["record_bytes_per_copy_on_screen"] = *r.record_bytes_per_copy_on_screen;
  if (r.animation) j["animation"] = animation_json(*r.animation);
  if (r.mesh_lod) j["mesh_lod"] = mesh_lod_json(*r.mesh_lod);
  if (r.drawn_error) j["drawn_error"] = drawn_error_json(*r.drawn_error);
  if (r.culling_audit) j["culling_audit"] = culling_audit_json(*r.culling_audit);
  if (r.instructions) j["instructions"] = instructions_json(*r.instructions);
  if (r.partial) {
    j["partial"] = true;
    j["frames_planned"] = r.frames_planned;
  }
  if (r.runs) {
    json runs = {{"count", r.runs->count}, {"median_ms", r.runs->median_ms}};
    if (!r.runs->pids.empty()) runs["pids"] = r.runs->pids;
    if (!r.runs->started_s.empty()) runs["started_s"] = r.runs->started_s;
    j["runs"] = runs;
  }
  if (r.pid) j["pid"] = *r.pid;
  if (r.started_s) j["started_s"] = *r.started_s;
  if (r.wall_s) j["wall_s"] = *r.wall_s;
  j["samples"] = samples;
  return j;
}

}  // namespace crowdprof

// The result of one bench run as crowdprof stores and reads it (bench --json,
// a baseline, each run of a compare or capacity result): one typed model that
// every report and gate takes, so a field is named in one place, the codec
// (result/result_codec.h), and a renamed one fails to compile, not at run time.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/modes.h"
#include "measuring/category_clock.h"
#include "measuring/counters.h"
#include "measuring/environment.h"
#include "measuring/gpu_passes.h"
#include "scene/cull_audit.h"

namespace crowdprof {

// The "crowdprof.format" this version writes; the codec reads it and the
// older ones below, and refuses any other with a line saying which it reads.
inline constexpr int kResultFormat = 2;
// Format 1 (crowdprof before 2026-11-26) keyed categories by the BGE's names
// ("Animations", "GPU Latency"); format 2 by their series ("animations_ms"),
// as CSV columns and metrics are. Both are read.
inline constexpr int kOldestResultFormat = 1;

// Result::digest_scheme this version writes.
inline constexpr int kDigestScheme = 2;

// Most runs a result may pool (check --runs).
inline constexpr size_t kMaxRuns = 100;

// One character of the crowd and the work its copies did in the last frame
// measured (a result stores copies_visible, copies_culled, poses_updated,
// vertices_skinned and copies_fallback of it).
struct CharacterRun {
  std::string file;          // as the scene names it
  std::string character;     // its name
  std::string content_hash;  // FNV-1a 64 of its file's bytes ("asset_hash"); empty in older results
  size_t copies = 0, joints = 0, vertices = 0, actions = 0;
  std::string action_choice;  // shared, random or weighted
  Counters counters;
};

// The camera's lens as the run used it (scene/camera.h's Lens, in doubles).
struct LensRecord {
  double focal_mm = 0, sensor_width_mm = 0, sensor_height_mm = 0;
  std::string sensor_fit;  // auto, horizontal or vertical
};

// Skinning baked into tables (--skinning baked): the bake and what it cost in
// fidelity against exact sampling.
struct BakeRecord {
  double rate_hz = 0;
  uint64_t samples = 0;
  double bake_ms = 0;
  double max_deviation = 0;           // model units
  double max_deviation_fraction = 0;  // of the character's height
};

// Skinning compute or baked: what the GPU holds for it.
struct GpuSkinningRecord {
  std::string skinning;  // "compute" or "baked"
  uint64_t gpu_bytes = 0;
  std::optional<BakeRecord> bake;  // baked only
};

// With animation sharing, update-rate LOD or a budget (issue 13): how updates
// were scheduled in the last frame and what it cost in fidelity.
struct AnimationRecord {
  std::vector<uint64_t> copies_by_rate;  // copies updated every 1, 2, 4, ... 64 frames
  uint64_t longest_gap_frames = 0;
  uint64_t budget_demotions = 0;
  double max_deviation = 0;                 // model units
  double deviation_fraction_of_height = 0;  // of the deviating copy's character
  uint64_t copies_checked = 0, copies_deviating = 0;
};

// Mesh LOD (issue 29): one level (0: the full mesh), the copies on screen at it
// in the last frame and the error it is drawn with: meshoptimizer's estimate of
// the level's distance from the full surface (bind pose; 0 at level 0), the
// worst character's (a level no character has: 0), in model units (mm for
// glTF's metres x 1000), as a share of that character's height, and in pixels
// at the largest copy drawn at the level (0 when none is).
struct MeshLevelRecord {
  uint64_t copies = 0;
  double error = 0, error_fraction = 0, error_px = 0;
};
struct MeshLodRecord {
  std::vector<MeshLevelRecord> levels;  // one to four
};

// What the run's savings cost in fidelity (issue 29 item 2;
// CrowdBench::measure_drawn_error): the last frame's copies on screen as drawn
// (shared, held by update-rate LOD or the budget, a baked blend; at their mesh
// level) against their exact, full-detail pose, per drawn vertex: its distance
// from the same vertex posed exactly, plus its level's error. Float positions:
// packed vertices' quantisation is not in it. And how often copies changed
// their update period (popping), per second of the run.
struct DrawnErrorRecord {
  uint64_t copies_checked = 0, copies_deviating = 0, vertices = 0, copy_stride = 1;
  double max = 0, rms = 0;                    // model units (mm = x 1000 for glTF's metres)
  double max_fraction = 0, rms_fraction = 0;  // of the character's height
  double max_px = 0, rms_px = 0;
  double mesh_max = 0;             // the largest mesh-level error included (model units)
  double switches_per_second = 0;  // changes of update period, all copies
};

// The drawn error a saving may cost and still count as unseen: a pixel.
// compare's Pareto front marks points past it; advise takes no lever past it
// unless --max-error says otherwise.
inline constexpr double kVisibleErrorPx = 1.0;

// The GPU's memory as the GL reports it (NVX_gpu_memory_info or ATI_meminfo),
// read when the renderer was made; "unknown" where the GL says nothing, with
// the largest storage block it allows.
struct GpuMemoryRecord {
  std::string source;  // "NVX_gpu_memory_info", "ATI_meminfo" or "unknown"
  std::optional<uint64_t> total_bytes, free_bytes;
  uint64_t max_storage_block_bytes = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
};

// What was run: the scene, the crowd, the mode and how it was timed.
struct RunDescription {
  std::string file;                              // the character's file (with #skin=N when chosen), or the scene file
  std::string character;                         // its name (of a mixed crowd: the names joined by " + ")
  size_t characters = 0;                         // copies in the crowd
  size_t joints = 0, vertices = 0, actions = 0;  // of a mixed crowd: the largest character's
  std::string action_choice;                     // "shared" or "random"; "scene": each character as its scene file says
  std::string action;                            // with shared: the action every copy plays ("" when there is none)
  uint32_t seed = 0;
  std::string mode;       // preset name, or "custom"
  ModeSwitches switches;  // what the mode set
  int threads = 1;
  std::string backend = "none", renderer = "none";
  // Empty when frames were timed on the GPU (GL timer queries), else why not.
  std::string gpu_timing_missing = "no GL backend (--backend none)";
  // The GPU timer's resolution (render/gpu_timer.h): a median GPU time below it
  // is shown as such, not as a number. 0: not known.
  double gpu_timer_resolution_ms = 0;
  // Empty when each pass's pipeline statistics were read, else why not.
  std::string pipeline_statistics_missing = "no GL backend (--backend none)";
  size_t warmup = 0;
  double fps = 60.0;
  std::string camera;
  std::string resolution;  // WxH: the frame's size and so the camera's aspect
  std::optional<LensRecord> lens;
  // When the run is of a scene file: its path and a hash of its contents.
  std::string scene_file, scene_hash;
  std::vector<CharacterRun> crowd;                // per character, in the scene's order
  std::optional<GpuSkinningRecord> gpu_skinning;  // skinning compute or baked
  std::optional<GpuMemoryRecord> gpu_memory;      // with a GL backend
};

// Per-frame samples in milliseconds, one per measured frame.
struct ResultSamples {
  std::vector<double> frame_ms;
  std::vector<double> cpu_ms;  // empty in results recorded before CPU time was
  std::array<std::vector<double>, kCategoryCount> category_ms;
  std::vector<double> gpu_ms;  // NaN where a frame's was not read back; empty when not timed
  // The same by pass (gpu_passes.h); each empty when the frame was not split.
  std::array<std::vector<double>, kGpuPassCount> gpu_pass_ms;
  // With a calibrated run: the probe's time after each frame, and each frame
  // over its probe (a ratio: the frame in the machine's speed of that moment).
  // Both empty otherwise.
  std::vector<double> probe_ms, calibrated;
  // Animations by stage, thread ms per frame (measuring/animation_stages.h);
  // all empty in results recorded before the split (2026-11-29).
  std::array<std::vector<double>, kAnimationStageCount> animation_stage_ms;
};

// The median counters per frame; results recorded before a counter existed
// lack it (present[i] false for kCounterFields[i]).
struct RecordedCounters {
  Counters values;
  std::array<bool, kCounterFields.size()> present{};
};

// Instructions per measured frame (bench --count-instructions, check --metric
// instructions), with what a baseline must match to be compared.
struct InstructionRecord {
  std::string source;               // "perf_event", "callgrind" or "none"
  std::optional<double> per_frame;  // callgrind's is filled in by who ran it
  int threads = 1;
  std::string simd, compiler;
  std::string problem;       // with "none": why nothing counted
  std::vector<double> runs;  // per process, when check pooled several
  // A timed baseline's work witness (gate/work_witness.h) counts a few frames
  // of its own, not the run's: how many, after how many uncounted. 0: the run's.
  size_t frames = 0, warmup = 0;
};

// Several runs of one scene pooled into one result (check --runs): the median
// of each run per metric, and each run's process and start.
struct PooledRuns {
  size_t count = 0;
  std::map<std::string, std::vector<double>> median_ms;  // by metric key (metric_samples)
  std::vector<int64_t> pids;
  std::vector<double> started_s;  // seconds after the first run started
};

struct Result {
  int format = kResultFormat;
  Environment environment;  // the build and machine (version, commit, CPU, SIMD, ...)
  RunDescription run;
  bool file_from_result = false;  // run.file is relative to the result's own folder
  ResultSamples samples;
  RecordedCounters counters;
  std::string digest;
  // Whether the digest hashes vertices skinned on the CPU (by the SIMD
  // kernels): false when the renderer skins every character (hwskin within its
  // bone limit, buffer, instanced, compute, baked), whose digest hashes
  // palettes and records no kernel computes, alike on every arithmetic.
  // Absent in older results: true, as they may have.
  bool digest_cpu_vertices = true;
  // The order the digest hashes each character's vertices in, the order the
  // bench skinned them: "joints" (ordered by their joints after loading,
  // asset/vertex_order.h, since 2026-11-27), or "file" (the file's order:
  // results without the key). Digests of runs that differ here differ by design.
  std::string vertex_order = "joints";
  // How the digest hashes mesh LOD: 2, a copy drawn whole hashes as without
  // mesh LOD (since 2026-11-30); 1, every copy's level (results without the
  // key). Mesh-LOD digests of the two differ by design.
  int digest_scheme = kDigestScheme;
  std::string stores;  // "streaming" or "regular" (skinning/output_stores.h); "" when not recorded
  // Bytes sent to GL buffers in a frame per copy on screen (bytes_uploaded over
  // copies_visible), the median of the frames with a copy on screen (0 without
  // one, or without a GL backend). Absent from results before 2026-11-29.
  std::optional<double> bytes_uploaded_per_copy_on_screen;
  // Its parts for GPU skinning (issue 52): palettes and per-copy records
  // (palette_bytes_uploaded, record_bytes_uploaded over copies_visible), each
  // the median as above. Absent from results before 2026-11-29's second.
  std::optional<double> palette_bytes_per_copy_on_screen, record_bytes_per_copy_on_screen;
  bool partial = false;       // stopped early (^C) ...
  size_t frames_planned = 0;  // ... of this many frames
  std::optional<AnimationRecord> animation;
  std::optional<MeshLodRecord> mesh_lod;  // with --mesh-lod on
  // The culling audit (issue 29), as scene/cull_audit.h records it.
  std::optional<CullingAudit> culling_audit;
  std::optional<DrawnErrorRecord> drawn_error;
  // Median per frame of each pass's pipeline statistics, when the GL had them.
  std::optional<std::array<std::array<double, kPipelineStatCount>, kGpuPassCount>> pipeline_statistics;
  // Vertex reuse, with the statistics: per pass, the median over frames of its
  // vertex-shader invocations over the vertices it drew (the vertices_drawn
  // counter, times the pass's draws of the crowd: one, or the shadow
  // cascades). 1: each vertex shaded once; NaN where the pass drew nothing.
  std::optional<std::array<double, kGpuPassCount>> invocations_per_vertex_drawn;
  std::optional<InstructionRecord> instructions;
  int calibration_probe = 0;  // the probe's version with samples.probe_ms, else 0
  std::optional<PooledRuns> runs;
  // The process that measured it, when several were (check --runs, the A/B).
  std::optional<int64_t> pid;
  std::optional<double> started_s, wall_s;
  // Each measured frame as the bench loop recorded it (per-frame counters: the
  // CSV's rows and the profile table's median frame), in the process that ran
  // it; record_samples() makes the stored columns above from them. Not stored:
  // a result read from a file has none.
  std::vector<FrameRecord> frame_records;

  size_t frames() const { return samples.frame_ms.size(); }
};

// Fills what a result stores of its frames from result.frame_records, once the
// run is over: the per-frame samples (GPU times only when a timer measured some
// frame; the calibrated ratio when the probe ran), the median of each counter
// and of each pass's pipeline statistics, and the instructions per frame
// counted by perf_event (callgrind's total is filled in by who ran it). A
// result without frame records that has samples (one read from a file) is
// left as it is.
void record_samples(Result& result);

// Times a frame of `passes` (modes.h) draws the crowd in `pass`: 0 for the
// skinning pass, the shadow cascades for shadows, else 1 when drawn.
uint32_t crowd_draws_in(GpuPass pass, uint32_t passes);

// The Animations category by stage: each stage's median thread ms over the
// frames, its share of the four medians' sum, the threads that ran them
// (run.threads on a parallel mode, else 1), and the median over frames of
// how much of Animations' thread time (its wall time x those threads) the
// stages cover. Empty without a split (older results) or when no stage took
// any time (nothing posed).
struct AnimationSplit {
  std::array<double, kAnimationStageCount> median_ms{}, share{};
  int threads = 1;
  double coverage = 0;
};
std::optional<AnimationSplit> animation_split(const Result& result);

// Index of the frame whose time is the median (the lower one for an even count).
size_t median_frame(const std::vector<FrameRecord>& frames);

// Each frame over its probe: samples.calibrated from frame_ms and probe_ms
// (empty when either is, or they differ in length; a probe of 0 gives NaN).
std::vector<double> calibrated_frames(const std::vector<double>& frame_ms, const std::vector<double>& probe_ms);

// The values that are numbers (a frame's NaN: not measured).
std::vector<double> finite(const std::vector<double>& values);

// The samples of a metric key: "frame_ms", "cpu_ms", "gpu_ms" or a category as
// the BGE names it ("Animations"). Null for another key, or cpu_ms/gpu_ms in a
// result without them.
const std::vector<double>* metric_samples(const Result& result, std::string_view key);

// Every metric key the result has samples of, in report order: frame_ms,
// cpu_ms (when recorded), the categories, gpu_ms (when timed).
std::vector<std::string> recorded_metrics(const Result& result);

// The median of a metric's samples, NaN ignored; 0 when it has none.
double metric_median(const Result& result, std::string_view key);

}  // namespace crowdprof

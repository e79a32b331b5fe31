#include "frame/run_bench.h"

#include "frame/bench_setup.h"

#include "measuring/instruction_counter.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <unistd.h>
#include <sstream>

#include "base/errors.h"
#include "frame/calibration_probe.h"
#include "base/switch_table.h"
#include "measuring/instruction_counter.h"

namespace crowdprof {

uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  uint64_t value = 0;
  while (meminfo >> key >> value >> unit)
    if (key == "MemAvailable:") return value * 1024;
  return 0;
}

namespace {

void require_fit(uint64_t needed, size_t copies) {
  uint64_t available = available_memory_bytes();
  if (available == 0 || needed <= available * 9 / 10) return;
  auto mib = [](uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; };
  throw UsageError(std::to_string(copies) + " copies of this character need about " + mib(needed) +
                   " of memory; this machine has " + mib(available) + " available");
}

}  // namespace

void check_fits_in_memory(const Character& character, size_t copies, const ModeSwitches& mode) {
  require_fit(estimate_bench_bytes(character, copies, mode), copies);
}

void check_fits_in_memory(std::span<const Character* const> characters, const BenchConfig& config) {
  require_fit(estimate_bench_bytes(characters, config.crowd, config.mode), config.crowd.copies);
}

namespace {

std::string_view choice_name(ActionChoice choice) {
  switch (choice) {
    case ActionChoice::Shared:
      return "shared";
    case ActionChoice::Random:
      return "random";
    case ActionChoice::Weighted:
      return "weighted";
  }
  return "?";
}

}  // namespace

RunDescription describe_run(const CrowdBench& bench, const std::string& file) {
  const Character& c = bench.character();
  const BenchConfig& config = bench.config();
  RunDescription run;
  run.file = file;
  run.characters = bench.crowd().size();
  std::vector<CrowdGroup> groups = crowd_groups(config.crowd);
  std::span<const Character* const> characters = bench.characters();
  for (size_t k = 0; k < characters.size(); ++k) {
    const Character& character = *characters[k];
    run.character += (k ? " + " : "") + character.name;
    run.joints = std::max(run.joints, character.skeleton.joint_count());
    run.vertices = std::max(run.vertices, character.mesh.vertex_count());
    run.actions = std::max(run.actions, character.actions.size());
    CharacterRun entry;
    entry.file = k < config.files.size() ? config.files[k] : file;
    entry.character = character.name;
    if (k < config.content_hashes.size()) entry.content_hash = config.content_hashes[k];
    entry.joints = character.skeleton.joint_count();
    entry.vertices = character.mesh.vertex_count();
    entry.actions = character.actions.size();
    for (const CrowdGroup& group : groups)
      if (group.character == k) {
        entry.copies += group.copies;
        entry.action_choice = choice_name(group.actions);
      }
    run.crowd.push_back(entry);
  }
  run.action_choice = config.actions_from_scene ? "scene" : std::string(choice_name(config.crowd.actions));
  if (!config.actions_from_scene && config.crowd.actions == ActionChoice::Shared &&
      static_cast<size_t>(config.crowd.shared_action) < c.actions.size())
    run.action = c.actions[static_cast<size_t>(config.crowd.shared_action)].name;
  run.seed = config.crowd.seed;
  run.mode = config.mode_name;
  const ModeSwitches& s = config.mode;
  run.switches = s;
  run.threads = s.parallel ? config.threads : 1;
  run.fps = config.fps;
  run.camera = config.camera;
  run.resolution = config.resolution;
  run.lens = LensRecord{config.lens.focal_mm, config.lens.sensor_width_mm, config.lens.sensor_height_mm,
                        std::string(to_string(config.lens.fit))};
  run.gpu_timing_missing = bench.gpu_timing_missing();
  run.pipeline_statistics_missing = bench.pipeline_statistics_missing();
  run.gpu_memory = bench.gpu_memory();
  run.scene_file = config.scene_file;
  run.scene_hash = config.scene_hash;
  if (s.skinning == SkinningSite::Compute || s.skinning == SkinningSite::Baked) {
    GpuSkinningRecord g{std::string(to_string(s.skinning)), bench.animation_gpu_bytes(), std::nullopt};
    if (s.skinning == SkinningSite::Baked) g.bake = bench.bake_summary();
    run.gpu_skinning = g;
  }
  return run;
}

void record_character_counters(const CrowdBench& bench, RunDescription& run) {
  std::span<const Counters> counters = bench.character_counters();
  for (size_t k = 0; k < run.crowd.size() && k < counters.size(); ++k) run.crowd[k].counters = counters[k];
  run.gpu_timer_resolution_ms = bench.gpu_timer_resolution_ms();  // measured on the first frame drawn
}

void record_animation(const CrowdBench& bench, Result& report) {
  const ModeSwitches& s = bench.config().mode;
  if (s.share_poses || s.update_lod || s.anim_budget_ms > 0) report.animation = bench.measure_animation();
}

void record_mesh_lod(const CrowdBench& bench, Result& report) {
  if (bench.config().mode.mesh_lod)
    report.mesh_lod = bench.mesh_lod_fidelity(resolution_size(bench.config().resolution).second);
}

void record_drawn_error(const CrowdBench& bench, Result& report) {
  DrawnErrorRecord e = bench.measure_drawn_error(resolution_size(bench.config().resolution).second);
  if (e.copies_checked == 0) return;
  // Over the measured frames, as every figure of the run: the warm-up's first,
  // slow frames demote copies the frames after it promote again.
  uint64_t switches = 0;
  for (const FrameRecord& frame : report.frame_records) switches += frame.rate_switches;
  const double seconds = static_cast<double>(report.frame_records.size()) / bench.config().fps;
  e.switches_per_second = seconds > 0 ? static_cast<double>(switches) / seconds : 0.0;
  report.drawn_error = e;
}

void record_culling_audit(const CrowdBench& bench, Result& report) {
  CullingAudit audit = bench.audit_culling();
  if (audit.copies > 0) report.culling_audit = audit;
}

void place_gpu_times(const CrowdBench& bench, size_t warmup, std::vector<FrameRecord>& frames) {
  for (const GpuTime& t : bench.gpu_times())
    if (t.frame >= warmup && t.frame - warmup < frames.size()) {
      // Each frame ends in glFinish, so its GPU work fits in its wall time. A
      // timer that says more is wrong (llvmpipe's first query of a long frame can
      // give the clock's absolute time): that frame counts as not read back.
      if (!(t.ms <= frames[t.frame - warmup].times.total_ms() * 1.5 + 1.0)) continue;
      frames[t.frame - warmup].gpu_ms = t.ms;
      frames[t.frame - warmup].gpu_passes = t.passes;
    }
}

Result run_bench(CrowdBench& bench, const std::string& file, const RunOptions& options) {
  Result report;
  report.run = describe_run(bench, file);
  report.run.warmup = options.warmup;
  report.environment = current_environment();
  size_t total = options.warmup + options.frames;
  std::vector<FrameRecord>& frames = report.frame_records;
  frames.reserve(options.frames);
  report.frames_planned = options.frames;
  InstructionCounter instructions;
  if (options.count_instructions) {
    instructions = InstructionCounter::open();
    // What a stored instruction baseline must match to be compared.
    InstructionRecord& i = report.instructions.emplace();
    i.source = instruction_source_name(instructions.source());
    if (instructions.source() == InstructionSource::None) i.problem = instructions.why_none();
    i.threads = report.run.threads;
    i.simd = report.environment.simd;
    i.compiler = report.environment.compiler;
  }
  std::unique_ptr<CalibrationProbe> probe;
  if (options.calibrate)
    probe = std::make_unique<CalibrationProbe>(bench.config().mode.parallel ? bench.config().threads : 1);
  for (size_t i = 0; i < total; ++i) {
    if (options.stop && options.stop->load()) {
      report.partial = true;
      break;
    }
    // Only the measured frames' work is counted, never the warm-up's.
    const bool measured = i >= options.warmup;
    if (measured) instructions.begin_frame();
    FrameRecord record = bench.step();
    if (measured) record.instructions = instructions.end_frame();
    // Right after the frame, outside it, so that both meet the same moment.
    if (probe) {
      record.probe_ms = probe->run();
      bench.restart_clock();  // the probe's time is not the next frame's Outside
    }
    if (measured) frames.push_back(record);
    place_gpu_times(bench, options.warmup, frames);
    if (options.progress) options.progress(i + 1, total);
  }
  if (instructions.failed()) {
    report.instructions->source = "none";
    report.instructions->problem = "a read of the hardware counter failed";
  }
  bench.collect_gpu_times();
  place_gpu_times(bench, options.warmup, frames);
  if (probe) report.calibration_probe = kCalibrationProbeVersion;
  // The culling audit runs outside the frames, so it is never counted, but
  // under callgrind it would take most of the process (35 s of 40 at 160 copies).
  finish_run(bench, report, instructions.source() != InstructionSource::Callgrind);
  return report;
}

void finish_run(const CrowdBench& bench, Result& result, bool audit_culling) {
  result.digest = bench.digest();
  result.digest_cpu_vertices = !bench.gpu_skinned();
  result.stores = bench.streams_output() ? "streaming" : "regular";
  record_character_counters(bench, result.run);
  record_animation(bench, result);
  record_mesh_lod(bench, result);
  record_drawn_error(bench, result);
  if (audit_culling) record_culling_audit(bench, result);
  record_samples(result);
}

std::function<void(size_t, size_t)> terminal_progress(bool quiet, const std::string& what) {
  if (quiet || !isatty(STDERR_FILENO)) return {};
  auto start = std::chrono::steady_clock::now();
  auto last = std::make_shared<std::chrono::steady_clock::time_point>(start);
  auto shown = std::make_shared<bool>(false);
  return [start, last, shown, what](size_t done, size_t total) {
    auto now = std::chrono::steady_clock::now();
    if (done >= total) {  // the end: erase the line, if one was shown
      if (*shown) std::fprintf(stderr, "\r\033[K");
      *shown = false;
      std::fflush(stderr);
      return;
    }
    if (now - start < std::chrono::seconds(1)) return;  // a short run shows nothing
    if (*shown && now - *last < std::chrono::milliseconds(100)) return;
    *last = now;
    *shown = true;
    double elapsed = std::chrono::duration<double>(now - start).count();
    double left = done > 0 ? elapsed / static_cast<double>(done) * static_cast<double>(total - done) : 0.0;
    std::fprintf(stderr, "\rcrowdprof: %s %zu/%zu frames, %.0f s left\033[K", what.c_str(), done, total, left);
    std::fflush(stderr);
  };
}

}  // namespace crowdprof

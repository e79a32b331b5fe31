// A whole benchmark run: warm-up, measured frames, and its result.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "asset/character.h"
#include "frame/crowd_bench.h"
#include "result/result.h"

namespace crowdprof {

struct RunOptions {
  size_t frames = 120;
  size_t warmup = 10;
  // Called after every frame with (frames done, frames in all), warm-up included.
  std::function<void(size_t, size_t)> progress;
  // When set and true, the run stops after the frame in progress (^C): the
  // report holds the frames measured so far and says it is partial.
  const std::atomic<bool>* stop = nullptr;
  // Count each measured frame's instructions on this thread
  // (measuring/instruction_counter.h); the caller makes the run one thread's.
  bool count_instructions = false;
  // Time the calibration probe after every frame, warm-up included, on the
  // bench's threads (frame/calibration_probe.h; check --metric calibrated).
  bool calibrate = false;
};

// Bytes of memory the machine can still give (MemAvailable), 0 if unknown.
uint64_t available_memory_bytes();

// Throws UsageError, before anything is allocated, when the crowd would not fit
// in the machine's available memory; the message says how much it needs.
void check_fits_in_memory(const Character& character, size_t copies, const ModeSwitches& mode);

// What a report says about a bench's scene and mode.
RunDescription describe_run(const CrowdBench& bench, const std::string& file);

// Copies the bench's last frame's per-character counters into run.crowd, and
// what the run learnt of its GPU timer (its resolution).
void record_character_counters(const CrowdBench& bench, RunDescription& run);

// Throws UsageError, before anything is allocated, when the config's crowd of
// these characters would not fit in the machine's available memory.
void check_fits_in_memory(std::span<const Character* const> characters, const BenchConfig& config);

// With sharing, update-rate LOD or a budget: report.animation from the
// bench's schedule and its fidelity measured on the last frame (docs/formats.md).
void record_animation(const CrowdBench& bench, Result& report);
// With mesh LOD: the copies per level and the error each is drawn with.
void record_mesh_lod(const CrowdBench& bench, Result& report);
// The culling audit of the bench's crowd and camera (any mode: it poses the
// copies exactly itself); nothing for an empty crowd.
void record_culling_audit(const CrowdBench& bench, Result& report);
// The last frame's drawn error against exact, full-detail poses (any mode: an
// exact one reports 0, the point a saving is weighed against).
void record_drawn_error(const CrowdBench& bench, Result& report);

// Runs options.warmup, then options.frames measured frames, and returns the
// finished result (finish_run).
Result run_bench(CrowdBench& bench, const std::string& file, const RunOptions& options);

// Once a bench's frames are in result.frame_records: what the bench learnt
// over the run (digest, per-character counters, the fidelity checks, the
// culling audit unless `audit_culling` is false) and the stored samples
// (record_samples).
void finish_run(const CrowdBench& bench, Result& result, bool audit_culling);

// Puts the GPU times the bench read in its last step (or collect) into the
// records of their frames: frame f is frames[f - warmup], when measured.
void place_gpu_times(const CrowdBench& bench, size_t warmup, std::vector<FrameRecord>& frames);

// Progress on stderr once a run has taken a second, only when a person watches
// (stderr is a terminal) and not quiet; an empty function otherwise. One line,
// redrawn in place: "crowdprof: <what> 120/1130 frames, 4 s left", where `what`
// names the mode and sweep point; erased when the run ends.
std::function<void(size_t, size_t)> terminal_progress(bool quiet, const std::string& what = "frame");

}  // namespace crowdprof

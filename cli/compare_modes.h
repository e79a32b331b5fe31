// What `compare` and `capacity` share (cli/cmd_compare.cpp): the modes as
// --modes names them, one bench per mode, and one interleaved run of them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cli/bench_options.h"
#include "frame/crowd_bench.h"
#include "reports/profile_table.h"
#include "render/bench_rendering.h"

// A mode as --modes names it: a preset, then any switches set away from it,
// PRESET+SWITCH=VALUE+..., e.g. master+lookups=bundled (the thesis's Fig. 8).
// Applies the switches to `run` and returns the preset's name; UsageError
// for an unknown preset or switch.
std::string apply_mode_spec(const std::string& spec, crowdprof::RunSpec& run);

// --modes checked (UsageError for a bad or repeated mode); empty: every preset.
std::vector<std::string> modes_to_run(const std::vector<std::string>& asked);

// UsageError unless --block is 1 to 1,000,000.
void check_block(long long block);

// The config of one mode: the shared options, with --threads applying only to
// the modes that run in parallel.
crowdprof::BenchConfig config_for(const crowdprof::RunSpec& shared, const std::string& mode,
                                  const crowdprof::BenchScene& scene);

struct ModeRun {
  std::vector<crowdprof::BenchConfig> configs;
  std::vector<std::unique_ptr<crowdprof::CrowdBench>> benches;
};

// Builds one bench per mode at `copies`; modes the user did not ask for by
// name are skipped, with a note, when they cannot run here (hwskin without GL).
ModeRun make_benches(const crowdprof::BenchScene& scene, std::vector<crowdprof::BenchConfig> configs, size_t copies,
                     bool named, bool note);

// The benches of `modes` interleaved in blocks of `block` frames (frame/compare.h),
// with --frames, --warmup, progress on a terminal naming `what`, and ^C.
std::vector<crowdprof::Result> run_modes(ModeRun& modes, const BenchCliOptions& options, size_t block,
                                            const crowdprof::BenchRendering& rendering, const std::string& what);

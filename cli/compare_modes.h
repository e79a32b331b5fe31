// What `compare` and `capacity` share (cli/cmd_compare.cpp): the modes as
// --modes names them, one bench per mode, and one interleaved run of them.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "cli/bench_options.h"
#include "frame/capacity.h"
#include "frame/compare.h"
#include "frame/crowd_bench.h"
#include "reports/profile_table.h"
#include "render/bench_rendering.h"

struct ModeRun {
  std::vector<crowdprof::BenchConfig> configs;
  std::vector<std::unique_ptr<crowdprof::CrowdBench>> benches;
};

// Builds one bench per mode at `copies`; modes the user did not ask for by
// name are skipped, with a note, when they cannot run here (hwskin without GL).
ModeRun make_benches(const crowdprof::BenchScene& scene, std::vector<crowdprof::BenchConfig> configs, size_t copies,
                     bool named, bool note);

// The benches of `modes` interleaved in blocks of `block` frames (frame/compare.h),
// with --frames, --warmup, progress on a terminal naming `what`, and ^C (or
// `stop`, when given, which the caller sets on ^C and on anything else).
std::vector<crowdprof::Result> run_modes(ModeRun& modes, const BenchCliOptions& options, size_t block,
                                         const crowdprof::BenchRendering& rendering, const std::string& what,
                                         const std::atomic<bool>* stop = nullptr);

// capacity's measurement of a round (frame/capacity.h): each active mode of
// `configs` at its size, side by side as run_modes runs them; `rounds`
// counts the rounds for the progress line; `stop` as run_modes'. Holds
// references to its arguments.
crowdprof::CapacityMeasure capacity_measure(const crowdprof::BenchScene& scene,
                                            const std::vector<crowdprof::BenchConfig>& configs,
                                            const BenchCliOptions& options, size_t block,
                                            const crowdprof::BenchRendering& rendering, size_t& rounds,
                                            const std::atomic<bool>* stop = nullptr);

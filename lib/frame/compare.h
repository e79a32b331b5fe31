// Several benches on one timeline: the modes of `crowdprof compare` run in
// blocks of frames, A B C A B C ..., so that drift of the machine (clock
// boosting, heat, another job starting) hits every mode alike instead of
// whichever ran last.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "asset/character.h"
#include "frame/crowd_bench.h"
#include "frame/run_bench.h"
#include "frame/bench_setup.h"
#include "result/result.h"
#include "result/sweep_axis.h"

namespace crowdprof {

// Throws UsageError, before anything is allocated, when the benches of
// `configs`, all alive at once, would not fit in the available memory.
void check_fits_in_memory(const Character& character, std::span<const BenchConfig> configs);
void check_fits_in_memory(std::span<const Character* const> characters, std::span<const BenchConfig> configs);

// The largest crowd, up to `cap`, whose bench of `config` fits its share of
// the memory when `side_by_side` benches are alive at once (the rule of
// check_fits_in_memory); 0 when not even one copy does.
size_t largest_crowd_in_memory(std::span<const Character* const> characters, BenchConfig config, size_t cap,
                               size_t side_by_side);

// Runs options.warmup then options.frames frames of every bench, `block` frames
// of one before the next (warm-up included, so each mode's caches are equally
// cold after the others ran). progress, if set, counts frames of all benches.
// One report per bench, in order, as run_bench would give.
std::vector<Result> run_interleaved(std::span<CrowdBench* const> benches, const std::string& file,
                                    const RunOptions& options, size_t block);

// A mode as --modes names it: a preset, then any switches set away from it,
// PRESET+SWITCH=VALUE+..., e.g. master+lookups=bundled (the thesis's Fig. 8).
// Applies the switches to `run` and returns the preset's name; UsageError
// for an unknown preset or switch.
std::string apply_mode_spec(const std::string& spec, RunSpec& run);

// --modes checked (UsageError for a bad or repeated mode); empty: every preset.
// The list as split at commas: the fields of a layer a mode sets
// (threaded+anim_layer=action=wave,mask=spine) are joined back to it.
std::vector<std::string> modes_to_run(const std::vector<std::string>& asked);

// UsageError unless --block is 1 to 1,000,000.
void check_block(long long block);

// The config of one mode: the shared options, with --threads applying only to
// the modes that run in parallel.
BenchConfig config_for(const RunSpec& shared, const std::string& mode, const BenchScene& scene);

// compare --sweep: the crowd sizes or counts of passes every mode runs at too.
struct Sweep {
  SweepAxis axis = SweepAxis::Characters;
  std::vector<size_t> points;  // ascending
};

// "n=10,20,40" or "10,20,40" (crowd sizes), "passes=1,2,4"; UsageError naming
// --sweep for anything else.
Sweep parse_sweep(const std::string& text);

}  // namespace crowdprof

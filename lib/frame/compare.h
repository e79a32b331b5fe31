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
#include "result/result.h"

namespace crowdprof {

// Throws UsageError, before anything is allocated, when the benches of
// `configs`, all alive at once, would not fit in the available memory.
void check_fits_in_memory(const Character& character, std::span<const BenchConfig> configs);
void check_fits_in_memory(std::span<const Character* const> characters, std::span<const BenchConfig> configs);

// Runs options.warmup then options.frames frames of every bench, `block` frames
// of one before the next (warm-up included, so each mode's caches are equally
// cold after the others ran). progress, if set, counts frames of all benches.
// One report per bench, in order, as run_bench would give.
std::vector<Result> run_interleaved(std::span<CrowdBench* const> benches, const std::string& file,
                                       const RunOptions& options, size_t block);

}  // namespace crowdprof

// Several runs of one scene, each measured in a process of its own, as one
// result (check --runs, --update-baseline): processes differ more than frames
// of one process do, so a gate that pools runs judges their medians.
#pragma once

#include <string>
#include <vector>

#include "result/result.h"

namespace crowdprof {

// Of several results of one run, the one whose median of samples `key` is the
// median (the lower middle of an even count): what --update-baseline records.
// `runs` must not be empty and each must hold samples `key`
// (std::invalid_argument otherwise).
Result median_run(std::vector<Result> runs, const std::string& key);

// The median run (median_run by `key`) with `runs` filled: how many, the median
// of each run for every metric they all recorded, and each run's pid and start
// (when every run has them, which are moved there). check_results judges runs
// instead of frames when both results pool at least kMannWhitneyMinSamples
// runs. `runs` must not be empty.
Result pooled_runs(std::vector<Result> runs, const std::string& key);

}  // namespace crowdprof

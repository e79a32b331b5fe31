// Results as Google Benchmark's JSON (--benchmark_format=json), so that the
// tools written for it read crowdprof's as they are: compare.py (Debian's
// libbenchmark-tools), github-action-benchmark, Bencher. Each run is a family
// of benchmarks, "<mode>/<character>/n:<copies>/<metric>": the frame (real_time
// the wall clock, cpu_time the CPU time of every thread) and each category
// that took time. As Google Benchmark writes repetitions, every frame is one
// "iteration" entry (so compare.py's U test has the frames as its samples),
// followed by the mean, median and stddev as "aggregate" entries.
#pragma once

#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/profile_table.h"

namespace crowdprof {

// The document for `runs`, in the order given (a comparison's modes, then its sweep).
nlohmann::json gbench_document(const std::vector<const Result*>& runs);

}  // namespace crowdprof

// Whether two results are runs of the same thing, and what differs between
// them that does not stop a comparison (machine, build, threads, scene file).
#pragma once

#include <string>
#include <vector>

#include "result/result.h"

namespace crowdprof {

// A field that makes two results runs of the same thing, and its two values as
// a user reads them in a message (strings quoted, numbers bare).
struct RunDifference {
  std::string field, a, b;
};

// The fields that make two results runs of the same thing, where they differ,
// in this order: the scene (file name, character, characters, joints, vertices,
// actions, action choice, camera, seed of a random choice, action, resolution),
// drawing or not, the mode and its switches, frames, warm-up and simulated fps.
// Counters and digest depend on all of these, so comparing them across a
// difference would mean nothing. The one list: check refuses on it, diff notes it.
std::vector<RunDifference> run_differences(const Result& a, const Result& b);

// InputError naming the baseline and the first of run_differences when the two
// results are not runs of the same thing.
void require_same_run(const Result& baseline, const Result& current, const std::string& baseline_path);

// What differs without stopping the comparison: a note per difference of
// thread count or GL backend, and one "warning: " line for another machine or
// build (CPU model, cores, build type, compiler, SIMD target). Lines for stderr
// after "crowdprof: note: ", except the warning, which has its own prefix.
std::vector<std::string> comparison_notes(const Result& baseline, const Result& current);

}  // namespace crowdprof

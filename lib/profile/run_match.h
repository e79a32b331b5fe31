// Whether two results are runs of the same thing, and what differs between
// them that does not stop a comparison (machine, build, threads, scene file).
#pragma once

#include <string>
#include <vector>

#include "profile/result.h"

namespace crowdprof {

// InputError naming the baseline and the first field that differs when the two
// results are not runs of the same thing: the scene (file name, character,
// characters, joints, vertices, actions, seed, camera), drawing or not, the
// mode and its switches, frames, warm-up and simulated fps. Counters and digest
// depend on all of these, so comparing them across a difference would mean
// nothing.
void require_same_run(const Result& baseline, const Result& current, const std::string& baseline_path);

// What differs without stopping the comparison: a note per difference of
// thread count or GL backend, and one "warning: " line for another machine or
// build (CPU model, cores, build type, compiler, SIMD target). Lines for stderr
// after "crowdprof: note: ", except the warning, which has its own prefix.
std::vector<std::string> comparison_notes(const Result& baseline, const Result& current);

}  // namespace crowdprof

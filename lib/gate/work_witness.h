// A timed check's second opinion: instructions per frame, counted once with
// the baseline and again when a check runs slower. A shared machine changes
// speed between the moment a baseline was recorded and the moment of a check
// (a neighbour's memory traffic, a quieter host an hour earlier) by more than
// the gate's tolerance, and no probe timed beside the frame follows every such
// change. The count does not move with the machine: where the time grew and
// the count did not, while the machine was seen to differ (other processes on
// the cores, the calibration probe's own time), the slowdown is the machine's
// as far as a stored baseline can tell, and the check warns instead of failing.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "measuring/other_load.h"
#include "result/result.h"

namespace crowdprof {

// Frames a witness counts (after kWitnessWarmup): under callgrind each frame
// of 160 thesis copies costs about 1.5 s, on top of about 6 s to start.
inline constexpr size_t kWitnessFrames = 3, kWitnessWarmup = 1;
// The count's tolerance: what `--metric instructions` allows (two processes
// count the same binary's frames within 0.1%).
inline constexpr double kWitnessTolerance = 0.01;
// What says the machine was not the one of the baseline: other processes and
// the hypervisor's steal took this much of a core together during the runs
// (the check's own moment, against none: the baseline's load is not
// recorded), or the calibration probe (work that never changes) ran this much
// slower or faster than the baseline's.
inline constexpr double kBusyNeighbourCores = 0.25, kProbeMoved = 0.05;

struct WorkWitness {
  double base = 0, current = 0;  // instructions per counted frame
  double change = 0;             // a fraction: +0.2 is 20% more
  size_t frames = 0;             // frames counted, each side
  std::string origin;            // what counted (source, SIMD target, compiler, threads)
  double tolerance = 0.07;       // the timed gate's: more work than this fails at once
  bool runs_differ = false;      // --timings-only: the two runs need not be of one scene
  OtherLoad load;                // during the check's last runs
  bool probe_known = false;
  double probe_change = 0;  // of the calibration probe's median time, against the baseline's
  enum class Verdict {
    MoreWork,      // grown beyond the timed tolerance: the build's slowdown, it fails at once
    OtherWork,     // moved beyond the count's 1% but not so far: the timed verdict stands
    MachineMoved,  // the same count, and the machine was seen to differ: a confirmed slowdown warns
    SameMachine,   // the same count, nothing seen of the machine: it fails (memory, threads)
  };
  Verdict verdict = Verdict::MoreWork;
  bool excuses() const { return verdict == Verdict::MachineMoved; }
  // What was seen of the machine, or "" when nothing: "other processes took
  // 0.98 of 2 cores during the runs; the calibration probe ran 94% slower than
  // when the baseline was recorded".
  std::string machine() const;
  // One line for stdout: "instructions per frame: 25,221,022 -> 25,221,022
  // (+0.0%; callgrind ...): the same work", with what it decided.
  std::string line() const;
};

// Fills change and verdict from the counts, the load and the probe.
void decide_witness(WorkWitness& witness);

// Whether a metric is timed on the CPU, where instructions per frame say what
// the work was; a GPU metric's slowdown is never excused by them.
bool cpu_timed_metric(const std::string& metric);

// What an instruction count was made with, in words: counts compare only
// within one ("callgrind (SIMD AVX2, GNU 12.2.0, 1 thread)").
std::string instruction_origin(const InstructionRecord& record);

// Counts this build's instructions as `like` was counted (its frames after its
// warm-up); nullopt with `problem` set where nothing counts or the run failed.
using CountWork = std::function<std::optional<InstructionRecord>(const InstructionRecord& like, std::string& problem)>;

// What was seen of the machine at the check (`load`, and the calibration
// probe's median time in `current` against `baseline`'s), then decide_witness.
void observe_machine(WorkWitness& witness, const Result& baseline, const Result& current, const OtherLoad& load);

// A check's timings moved (`slower` says how, for the note on stderr): this
// build's count beside the baseline's witness, where the baseline holds one and
// `count` counts alike; nullopt, with a note saying why, where not.
std::optional<WorkWitness> witness_count(const Result& baseline, const Result& current, const CountWork& count,
                                         const std::function<OtherLoad()>& load, const std::string& slower,
                                         double tolerance);

}  // namespace crowdprof

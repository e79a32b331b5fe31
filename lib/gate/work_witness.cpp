#include "gate/work_witness.h"

#include <cctype>
#include <cmath>
#include <iostream>

#include "base/number_text.h"
#include "frame/interrupt.h"
#include "measuring/stats.h"

namespace crowdprof {

namespace {

bool busy(const WorkWitness& w) {
  return w.load.known && w.load.others_cores + w.load.steal_cores >= kBusyNeighbourCores;
}

bool probe_moved(const WorkWitness& w) {
  return w.probe_known && std::abs(w.probe_change) >= kProbeMoved;
}

}  // namespace

void decide_witness(WorkWitness& w) {
  w.change = w.base > 0 ? w.current / w.base - 1 : 0;
  if (w.change > w.tolerance)
    w.verdict = WorkWitness::Verdict::MoreWork;
  else if (std::abs(w.change) > kWitnessTolerance)
    w.verdict = WorkWitness::Verdict::OtherWork;
  else
    w.verdict = busy(w) || probe_moved(w) ? WorkWitness::Verdict::MachineMoved : WorkWitness::Verdict::SameMachine;
}

bool cpu_timed_metric(const std::string& metric) {
  std::string lower;
  for (char c : metric) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower.find("gpu") == std::string::npos;
}

std::string WorkWitness::machine() const {
  std::string seen;
  auto add = [&](const std::string& part) { seen += (seen.empty() ? "" : "; ") + part; };
  if (busy(*this)) {
    if (load.others_cores >= 0.01)
      add("other processes took " + fixed(load.others_cores, 2) + " of " + std::to_string(load.cores) +
          " cores during the runs");
    if (load.steal_cores >= 0.01)
      add("the hypervisor gave " + fixed(load.steal_cores, 2) + " cores to other guests (steal)");
  }
  if (probe_moved(*this))
    add("the calibration probe, whose work never changes, ran " + fixed(std::abs(probe_change) * 100, 0) + "% " +
        (probe_change > 0 ? "slower" : "faster") + " than when the baseline was recorded");
  return seen;
}

std::string WorkWitness::line() const {
  std::string text = "instructions per frame: " + with_thousands(static_cast<uint64_t>(std::llround(base))) + " -> " +
                     with_thousands(static_cast<uint64_t>(std::llround(current))) + " (" + percent(change) +
                     ", tolerance " + percent(kWitnessTolerance).substr(1) + "; " + std::to_string(frames) +
                     " frames counted by " + origin + "): ";
  switch (verdict) {
    case Verdict::MoreWork:
      return text + "more work per frame, beyond the " + percent(tolerance).substr(1) + " tolerance: " +
             (runs_differ ? "the runs differ (--timings-only), and so does their work" : "the slowdown is the build's");
    case Verdict::OtherWork:
      return text + (change > 0 ? "more work per frame, within the tolerance" : "less work per frame") +
             ": the timed verdict stands";
    case Verdict::MachineMoved:
      return text + "the same work, on a machine that was not as it was for the baseline (" + machine() + ")";
    case Verdict::SameMachine:
      return text + "the same work, and nothing seen of the machine that explains the time";
  }
  return text;
}

std::string instruction_origin(const InstructionRecord& i) {
  auto known = [](const std::string& text) { return text.empty() ? std::string("?") : text; };
  return known(i.source) + " (SIMD " + known(i.simd) + ", " + known(i.compiler) + ", " + std::to_string(i.threads) +
         " thread)";
}

namespace {

// The calibration probe's median time, where a result has one.
std::optional<double> probe_median(const Result& result) {
  if (result.samples.probe_ms.empty()) return std::nullopt;
  return summarize(result.samples.probe_ms).median;
}

}  // namespace

void observe_machine(WorkWitness& witness, const Result& baseline, const Result& current, const OtherLoad& load) {
  witness.load = load;
  std::optional<double> base = probe_median(baseline), now = probe_median(current);
  witness.probe_known = base && now && *base > 0;
  witness.probe_change = witness.probe_known ? *now / *base - 1 : 0;
  decide_witness(witness);
}

std::optional<WorkWitness> witness_count(const Result& baseline, const Result& current, const CountWork& count,
                                         const std::function<OtherLoad()>& load, const std::string& slower,
                                         double tolerance) {
  if (!count || !baseline.instructions || !baseline.instructions->per_frame || baseline.instructions->frames == 0)
    return std::nullopt;
  const InstructionRecord& base = *baseline.instructions;
  std::cerr << "crowdprof: note: slower than the baseline (" << slower
            << "): counting this build's instructions per frame as the baseline's were (" << base.frames
            << " frames)\n";
  std::string problem;
  std::optional<InstructionRecord> now = count(base, problem);
  if (!now) {
    if (interrupt_requested().load())
      std::cerr << "crowdprof: interrupted: instructions are not compared from a cut run\n";
    else
      std::cerr << "crowdprof: note: instructions not counted (" << problem << "): the timed verdict stands\n";
    return std::nullopt;
  }
  if (instruction_origin(base) != instruction_origin(*now)) {
    std::cerr << "crowdprof: note: the baseline's instructions were counted by " << instruction_origin(base)
              << ", this build's by " << instruction_origin(*now) << ": not compared; the timed verdict stands\n";
    return std::nullopt;
  }
  WorkWitness witness;
  witness.base = *base.per_frame;
  witness.current = *now->per_frame;
  witness.frames = base.frames;
  witness.origin = instruction_origin(*now);
  witness.tolerance = tolerance;
  observe_machine(witness, baseline, current, load ? load() : OtherLoad{});
  return witness;
}

}  // namespace crowdprof

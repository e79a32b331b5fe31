// `crowdprof advise`: how to fit a crowd in a frame budget on the CPU. From
// the configuration the user gives, a greedy search: each step measures the
// next setting of every lever family added to the configuration of the
// moment, side by side with it (compare's interleaving, through
// AdviseHooks::measure), and takes the one that saves most milliseconds per
// pixel of drawn error it adds, until the budget is met, no lever saves time
// outside its interval, or every saving would draw past the error allowed.
// Two refinements of that rule: a lever that meets the budget on its own
// beats every one that does not (among them, the least error added wins), and
// one that adds no visible error (under 0.01 px) beats one that adds some.
// Then capacity's search of the start and of the end (AdviseHooks::capacity).
//
// The search is a pure function of what the hooks measure, so it is tested
// against fake costs; cli/cmd_advise.cpp makes the benches. GPU levers are not
// tried: timed on llvmpipe they would give wrong advice.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/errors.h"
#include "base/modes.h"
#include "frame/capacity.h"
#include "result/advice_record.h"
#include "result/result.h"

namespace crowdprof {

// The lever families, in the order a step lists them: sharing (share on, its
// quantum), update_lod (on, then coarser thresholds), mesh_lod (likewise),
// anim_budget (half the Animations median, again each step), threads (every
// core), vertex_format (packed).
std::span<const std::string_view> lever_families();
// "sharing, update_lod, ...".
std::string lever_family_names();

// A configuration: a preset, the switches set over it (by name, as typed)
// and the threads (0: every core).
struct AdviseConfig {
  std::string preset = "threaded";
  std::map<std::string, std::string> switches;
  int threads = 0;
  ModeSwitches mode_switches() const;  // the preset with the switches applied
  bool operator==(const AdviseConfig&) const = default;
};

struct AdviseRule {
  double budget_ms = 1000.0 / 60.0;
  CapacityMetric metric;                  // what must fit: the frame or Animations
  double max_error_px = kVisibleErrorPx;  // a lever that would draw the crowd further off is not taken
  std::vector<std::string> levers;        // families to try (lever_families()); empty: all
  int cores = 1;                          // of this machine, for the threads lever
  size_t characters = 0;                  // the crowd measured, for the estimated capacities
  size_t side_by_side = 8;                // most configurations measured at once (memory)
  double time_limit_s = 180;              // no step starts after it
  // Empty when the rule can run, else why not, naming the setting ({budget},
  // {max_error}, {levers}, {time_limit}).
  SettingText Validate() const;
};

// The next setting of each family over `current`, whose run is `base`: one
// per family that has one, in lever_families()' order. `changes` is what it
// adds as options ("--share on --share-quantum 0.0167"); `why_not` is set when
// it cannot run with the configuration (conflicts(), in settings' names).
struct LeverSetting {
  std::string family;
  AdviseConfig config;
  std::string changes;
  SettingText why_not;
};
std::vector<LeverSetting> next_lever_settings(const AdviseRule& rule, const AdviseConfig& current, const Result& base);

struct AdviseHooks {
  // Runs the configurations side by side, interleaved: one result per
  // configuration, in order. A partial result: the run was stopped.
  std::function<std::vector<Result>(std::span<const AdviseConfig>)> measure;
  // Capacity's search of the configurations (start, final) at the rule's budget and metric.
  std::function<CapacityRun(std::span<const AdviseConfig>)> capacity;
  // Why a measurement came back partial: "interrupted" or "time limit".
  std::function<std::string()> stop_reason;
  // Seconds since the search began.
  std::function<double()> elapsed_s;
  // A line of progress ("step 2: 6 configurations ...").
  std::function<void(const std::string&)> progress;
};

struct AdviseRun {
  AdviceRecord record;
  AdviseConfig start, final;
  std::optional<Result> start_run, final_run;  // as measured (final: its last measurement)
  bool partial = false;                        // interrupted
};

// The search. Validate() the rule first.
AdviseRun run_advise(const AdviseRule& rule, const AdviseConfig& start, const AdviseHooks& hooks);

// The options a configuration sets over `start`, as users type them:
// "--share on --share-quantum 0.0333 --threads 2"; "" when none.
std::string options_over(const AdviseConfig& start, const AdviseConfig& config);

}  // namespace crowdprof

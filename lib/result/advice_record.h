// What `crowdprof advise` found (its --json, kind "advise"): the question
// (budget, metric, error allowed), then per step every lever it measured
// beside the configuration of the moment, which it took and why the others
// were not, and the outcome. The runs of the start and of the final
// configuration are the document's "runs", as bench results.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "result/result.h"

namespace crowdprof {

// A median and its bootstrap interval (gate/paired_test.h), in ms.
struct MsInterval {
  double median = 0, low = 0, high = 0;
};

// One configuration measured in a step: the step's base (lever empty) or the
// base with one lever added.
struct AdviceCandidate {
  std::string lever;    // its family: "sharing", "update_lod", "mesh_lod", "anim_budget", "threads", "vertex_format"
  std::string changes;  // the options it adds, as users type them: "--share on --share-quantum 0.0333"
  MsInterval metric;    // the metric's median over its frames
  double frame_ms = 0;  // the frame's median (the metric's with --metric frame)
  // The base's metric minus this one's, frame by frame (paired: the two ran in
  // the same blocks), its median and interval; positive: it saves time.
  MsInterval saved;
  // The drawn error of the whole configuration (the base's own plus this
  // lever's): the largest over the copies checked. Not measured (all 0) when
  // no copy was on screen, or for a lever that could not run.
  bool error_measured = true;
  double error_px = 0, error_mm = 0, error_height_pct = 0;
  // Copies the budget holds at this cost per copy: n x budget / metric,
  // estimated (the search measures only the start and the end).
  size_t capacity_estimate = 0;
  std::string digest;
  // "taken", or why not: "noise" (the saving's interval reaches 0), "slower",
  // "past max error", "not the best" (another saved more per pixel), "base".
  std::string verdict;
};

struct AdviceStep {
  std::vector<AdviceCandidate> candidates;  // the base first
  std::optional<size_t> taken;              // index into candidates
};

// Capacity's search (frame/capacity.h) of one configuration.
struct AdviceCapacity {
  std::string configuration;   // "start" or "final"
  std::optional<size_t> fit;   // the largest crowd within the budget (none: not even one)
  std::optional<size_t> over;  // the smallest crowd found over it (none: the cap fits)
  bool capped = false;
  size_t measured = 0;  // sizes it tried
};

struct AdviceRecord {
  double budget_ms = 0;
  std::string metric = "frame";  // or "Animations"
  double max_error_px = 1;
  double time_limit_s = 180;
  size_t characters = 0;
  std::string start_mode;             // the preset it started from, with the user's switches
  std::string start_options;          // the options the start sets over its preset, as users type them
  std::string final_options;          // the options the final configuration sets over the preset: a command line
  std::string added_options;          // what the final configuration changes from the start
  std::vector<std::string> levers;    // the families it could try
  std::vector<std::string> left_out;  // what it does not try, and why (GPU levers on llvmpipe)
  // The start measured alone (verdict "start") and the final configuration's
  // last measurement (verdict "final": the start's, a step's base or its
  // taken lever); their saved_ms is 0 (they are not a pair).
  AdviceCandidate start, final;
  std::vector<AdviceStep> steps;
  size_t configurations_measured = 0;
  size_t frames_per_configuration = 0, warmup = 0, block_frames = 0;
  bool met = false;  // the final configuration's median is within the budget
  // "met", "no lever left", "max error", "noise", "time limit" or "interrupted".
  std::string outcome;
  std::string ran_out;                     // when not met: which lever ran out and why, in a sentence
  std::vector<AdviceCapacity> capacities;  // start and final, when measured
  double elapsed_s = 0;
};

// The "advice" object of advise --json, and back, every field checked
// (InputError naming `path`).
nlohmann::json advice_to_json(const AdviceRecord& advice);
AdviceRecord advice_from_json(const nlohmann::json& advice, const std::string& path);

}  // namespace crowdprof

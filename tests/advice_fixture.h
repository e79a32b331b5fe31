// An advise search's record made up by hand, for testing what reads it (the
// HTML page, the result document) without running the search: two steps, the
// first taking sharing over update_lod (noise) and mesh_lod (past the error
// allowed), the second taking update_lod while mesh_lod cannot run.
#pragma once

#include <string>

#include "result/advice_record.h"

namespace crowdprof::test {

inline AdviceCandidate advice_candidate(const std::string& lever, MsInterval metric, MsInterval saved, double px,
                                        const std::string& verdict) {
  AdviceCandidate c;
  c.lever = lever;
  c.changes = lever.empty() ? "" : "--" + lever + " on";
  c.metric = metric;
  c.frame_ms = metric.median;
  c.saved = saved;
  c.error_px = px;
  c.error_mm = px * 3;
  c.error_height_pct = px / 2;
  c.capacity_estimate = metric.median > 0 ? static_cast<size_t>(160 * 16.7 / metric.median) : 0;
  c.digest = "00000000000000aa";
  c.verdict = verdict;
  return c;
}

// met: the budget reached in two steps; not met: the search stops after the
// first, its only saving inside its interval.
inline AdviceRecord sample_advice(bool met) {
  AdviceRecord a;
  a.budget_ms = 16.7;
  a.metric = "frame";
  a.max_error_px = 1;
  a.characters = 160;
  a.start_mode = "threaded";
  a.start_options = "--mode threaded";
  a.levers = {"sharing", "update_lod", "mesh_lod"};
  a.left_out = {"GPU levers (hwskin, passes): timed on llvmpipe they would give wrong advice"};
  a.frames_per_configuration = 40;
  a.warmup = 5;
  a.block_frames = 10;
  a.elapsed_s = 61;
  AdviceStep first;
  first.candidates = {
      advice_candidate("", {24, 23.5, 24.6}, {}, 0.1, "base"),
      advice_candidate("sharing", {19, 18.7, 19.4}, met ? MsInterval{5, 4.6, 5.3} : MsInterval{0.3, -0.2, 0.8}, 0.4,
                       met ? "taken" : "noise"),
      advice_candidate("update_lod", {23.8, 23.1, 24.4}, {0.2, -0.1, 0.5}, 0.3, "noise"),
      advice_candidate("mesh_lod", {14, 13.8, 14.3}, {10, 9.6, 10.4}, 2.5, "past max error")};
  if (met) first.taken = 1;
  a.steps.push_back(first);
  a.start = first.candidates.front();
  a.start.verdict = "start";
  a.final = a.start;
  if (met) {
    AdviceStep second;
    AdviceCandidate cannot = advice_candidate("mesh_lod", {}, {}, 0, "cannot run: mesh_lod needs update_lod off");
    cannot.capacity_estimate = 0;
    second.candidates = {advice_candidate("", {19.1, 18.8, 19.5}, {}, 0.4, "base"),
                         advice_candidate("update_lod", {15.9, 15.6, 16.2}, {3.2, 2.9, 3.5}, 0.6, "taken"), cannot};
    second.taken = 1;
    a.steps.push_back(second);
    a.final = second.candidates[1];
    a.final_options = "--mode threaded --sharing on --update_lod on";
    a.added_options = "--sharing on --update_lod on";
    a.capacities = {{"start", 110, 112, false, 7}, {"final", 165, 168, false, 8}};
    a.configurations_measured = 7;
    a.met = true;
    a.outcome = "met";
  } else {
    a.final_options = a.start_options;
    a.configurations_measured = 4;
    a.outcome = "noise";
    a.ran_out = "the best saving, sharing's 0.3 ms, reaches 0 in its interval: more frames would tell";
  }
  a.final.verdict = "final";
  a.final.saved = {};
  return a;
}

}  // namespace crowdprof::test

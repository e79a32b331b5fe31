// A finished run and the three ways crowdprof reports it: the BGE's profile
// overlay as text, one CSV row per frame, and a JSON summary (docs/formats.md).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "profile/counters.h"
#include "profile/environment.h"

namespace crowdprof {

// One character of the crowd and the work its copies did in the last frame
// measured (counters that only count in all, draw calls and bytes, stay 0).
struct CharacterRun {
  std::string file;       // as the scene names it
  std::string character;  // its name
  size_t copies = 0, joints = 0, vertices = 0, actions = 0;
  std::string action_choice;  // shared, random or weighted
  Counters counters;
};

struct RunDescription {
  std::string file;        // the character's file (with #skin=N when chosen), or the scene file
  std::string character;   // its name (of a mixed crowd: the names joined by " + ")
  size_t characters = 0;   // copies in the crowd
  size_t joints = 0, vertices = 0, actions = 0;  // of a mixed crowd: the largest character's
  std::string action_choice;  // "shared" or "random"; "scene": each character as its scene file says
  std::string action;         // with shared: the action every copy plays ("" when there is none)
  uint32_t seed = 0;
  std::string mode;            // preset name, or "custom"
  nlohmann::json switches;     // the mode's switches by name
  int threads = 1;
  std::string backend = "none", renderer = "none";
  // Empty when frames were timed on the GPU (GL timer queries), else why not.
  std::string gpu_timing_missing = "no GL backend (--backend none)";
  // The GPU timer's resolution (render/gpu_timer.h): a median GPU time below it
  // is shown as such, not as a number. 0: not known.
  double gpu_timer_resolution_ms = 0;
  size_t warmup = 0;
  double fps = 60.0;
  std::string camera;
  std::string resolution;  // WxH: the frame's size and so the camera's aspect
  nlohmann::json lens;     // focal_mm, sensor_width_mm, sensor_height_mm, sensor_fit
  // When the run is of a scene file: its path and a hash of its contents.
  std::string scene_file, scene_hash;
  std::vector<CharacterRun> crowd;  // per character, in the scene's order
  // Skinning compute or baked: what the GPU holds for it ("gpu_bytes") and, for
  // baked, the bake (rate_hz, bake_ms, samples) and the largest vertex deviation
  // from exact sampling (max_deviation in model units, max_deviation_fraction
  // of the character's height). Null in other modes.
  nlohmann::json gpu_skinning;
};

struct RunReport {
  RunDescription run;
  Environment environment;
  std::vector<FrameRecord> frames;  // after warm-up
  std::string digest;
  // How CPU skinning stored float vertices: "streaming" or "regular"
  // (skinning/output_stores.h); left out of the JSON when empty.
  std::string stores;
  // A run stopped early (^C): frames holds fewer than frames_planned.
  bool partial = false;
  size_t frames_planned = 0;
  // With animation sharing, update-rate LOD or a budget (issue 13): how updates
  // were scheduled and what it cost in fidelity (docs/formats.md); null otherwise.
  nlohmann::json animation;
  // How the frames' instructions were counted: "" (not asked), "perf_event",
  // "callgrind" (the total is read from callgrind's output by who ran it) or
  // "none" (asked, but nothing here counts; instruction_problem says why).
  std::string instruction_source;
  std::string instruction_problem;
};

// Index of the frame whose time is the median (the lower one for an even count).
size_t median_frame(const std::vector<FrameRecord>& frames);

// The BGE overlay for the median frame, then a line describing the run.
std::string format_profile(const RunReport& report);

// Header, then one row per frame (docs/formats.md).
void write_csv(const RunReport& report, std::ostream& out);
std::string csv_header();

// The summary document (docs/formats.md), with the per-frame samples that
// `check` compares.
nlohmann::json to_json(const RunReport& report);

}  // namespace crowdprof

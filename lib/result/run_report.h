// A finished run as the bench loop hands it over: its frames one by one, before
// make_result turns them into the stored result (result.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "measuring/counters.h"
#include "measuring/environment.h"
#include "result/result.h"

namespace crowdprof {

struct RunReport {
  RunDescription run;
  Environment environment;
  std::vector<FrameRecord> frames;  // after warm-up
  std::string digest;
  // Whether the digest hashes vertices skinned on the CPU (by the SIMD
  // kernels): false when the renderer skins every character (hwskin within its
  // bone limit, buffer, instanced, compute, baked), whose digest hashes
  // palettes and records no kernel computes, alike on every arithmetic.
  bool digest_cpu_vertices = true;
  // How CPU skinning stored float vertices: "streaming" or "regular"
  // (skinning/output_stores.h); left out of the JSON when empty.
  std::string stores;
  // A run stopped early (^C): frames holds fewer than frames_planned.
  bool partial = false;
  size_t frames_planned = 0;
  // With animation sharing, update-rate LOD or a budget (issue 13): how updates
  // were scheduled and what it cost in fidelity (docs/formats.md); null otherwise.
  std::optional<AnimationRecord> animation;
  // With mesh LOD (issue 29): copies per level and the error each is drawn with.
  std::optional<MeshLodRecord> mesh_lod;
  std::optional<CullingAuditRecord> culling_audit;
  std::optional<DrawnErrorRecord> drawn_error;
  // How the frames' instructions were counted: "" (not asked), "perf_event",
  // "callgrind" (the total is read from callgrind's output by who ran it) or
  // "none" (asked, but nothing here counts; instruction_problem says why).
  std::string instruction_source;
  std::string instruction_problem;
  // The calibration probe's version when each frame was followed by it
  // (frame/calibration_probe.h), else 0.
  int calibration_probe = 0;
};

// Index of the frame whose time is the median (the lower one for an even count).
size_t median_frame(const std::vector<FrameRecord>& frames);

// The run as crowdprof stores it: per-frame samples, and the median of each
// counter over the frames (they rarely vary at all).
Result make_result(const RunReport& report);

// result_to_json(make_result(report)): the summary document (docs/formats.md).
nlohmann::json to_json(const RunReport& report);

}  // namespace crowdprof

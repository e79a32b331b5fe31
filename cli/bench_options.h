// The options `bench` shares with the commands that run benches (compare,
// check): the scene, the mode and its switches, the clock.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "asset/character.h"
#include "frame/crowd_bench.h"
#include "output/output_file.h"
#include "render/bench_rendering.h"

#include <climits>

inline constexpr long long kThreadsUnset = LLONG_MIN;

struct BenchCliOptions {
  std::string file;
  long long characters = 160;
  std::string actions = "shared";
  std::string action;  // with shared: which action (default: the first)
  long long seed = 1;
  long long frames = 120;
  long long warmup = 10;
  double fps = 60.0;
  std::string mode = "threaded";
  long long threads = kThreadsUnset;  // all cores in parallel modes
  std::string camera = "default";
  std::string backend = "none";  // auto, egl, osmesa or none
  std::string resolution = "1600x900";  // the frame's size in pixels, and the camera's aspect
  bool allow_static = false;
  bool quiet = false;
  // Switch overrides; empty keeps the mode's.
  std::string lookups, culling, pose, parallel, skinning;
  std::string csv, json, trace;
  std::string screenshot;  // bench: the last frame as a PNG
};

void add_bench_options(CLI::App& cmd, BenchCliOptions& options);

// "WxH" as {W, H}, each 1 to 65536; throws UsageError naming --resolution.
std::pair<int, int> parse_resolution(const std::string& value);

// Checks every value that does not depend on the character (UsageError with
// the option's name).
void validate_bench_options(const BenchCliOptions& options);

// Checks every value (UsageError with the option's name) and builds the config.
crowdprof::BenchConfig make_bench_config(const BenchCliOptions& options, const crowdprof::Character& character);

// UsageError, before any work, when --csv, --json, --trace or --screenshot (and
// the command's `outputs`) cannot be written, when one of them is the character
// file (or one of the command's `inputs`), or when two of them share a path.
void require_writable_outputs(const BenchCliOptions& options, std::vector<crowdprof::NamedPath> inputs = {},
                              std::vector<crowdprof::NamedPath> outputs = {});

// Opens --backend at --resolution for the config's crowd and points
// config.renderer at its renderer (left null for none). When auto finds no GL,
// says so on stderr and goes on without.
crowdprof::BenchRendering open_bench_rendering(const BenchCliOptions& options, const crowdprof::Character& character,
                                               crowdprof::BenchConfig& config);

// The options `bench` shares with the commands that run benches (compare,
// check): the scene, the mode and its switches, the clock.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "asset/character.h"
#include "frame/crowd_bench.h"

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
  std::string backend = "none";
  bool allow_static = false;
  bool quiet = false;
  // Switch overrides; empty keeps the mode's.
  std::string lookups, culling, pose, parallel, skinning;
  std::string csv, json;
};

void add_bench_options(CLI::App& cmd, BenchCliOptions& options);

// Checks every value (UsageError with the option's name) and builds the config.
crowdprof::BenchConfig make_bench_config(const BenchCliOptions& options, const crowdprof::Character& character);

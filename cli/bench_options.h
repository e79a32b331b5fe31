// The options `bench` shares with the commands that run benches (compare,
// check): the scene, the mode and its switches, the clock.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "asset/character.h"
#include "frame/crowd_bench.h"
#include "output/output_file.h"
#include "render/bench_rendering.h"
#include "scene/scene_file.h"

#include <climits>
#include <memory>

inline constexpr long long kThreadsUnset = LLONG_MIN;

struct BenchCliOptions {
  std::string file;  // a character (.glb, .gltf) or a scene file (.json)
  long long characters = 160;
  // shared, random, or (from a baseline of a scene file) scene; empty: shared,
  // or each character's actions as its scene file says.
  std::string actions;
  std::string action;  // with shared: which action (default: the first)
  long long seed = 1;
  long long frames = 120;
  long long warmup = 10;
  double fps = 60.0;
  double bake_rate = 30.0;  // mode baked: samples per second (animation/bake.h)
  std::string mode = "threaded";
  long long threads = kThreadsUnset;  // all cores in parallel modes
  std::string camera = "default";
  std::string backend = "none";  // auto, egl, osmesa or none
  std::string resolution = "1600x900";  // the frame's size in pixels, and the camera's aspect
  bool allow_static = false;
  bool quiet = false;
  // Switch overrides; empty keeps the mode's.
  std::string lookups, culling, pose, parallel, skinning, palettes, draw;
  std::string vertex_format;  // float or packed (skinning/packed_vertex.h)
  // Issue 13's switches (docs/modes.md); empty keeps the mode's.
  std::string share, share_quantum, update_lod, lod_thresholds, anim_budget;
  std::string csv, json, trace;
  std::string screenshot;  // bench: the last frame as a PNG
  std::string html;        // the HTML report of the run (docs/report.md)
  double lens = 0;  // focal length in mm; 0: the scene's, else Blender's default 35 mm
  // To tell options given on the command line (which override a scene file)
  // from defaults: the command they were parsed by, and those check set from
  // a baseline as if given.
  CLI::App* command = nullptr;
  std::set<std::string> adopted;
  bool given(const std::string& option) const {
    return (command && command->count(option) > 0) || adopted.count(option) > 0;
  }
};

// What a bench runs on: the characters loaded, and the scene file when the
// run is of one. Characters keep their addresses (benches point at them).
struct BenchScene {
  std::optional<crowdprof::SceneFile> scene;
  std::vector<std::unique_ptr<crowdprof::Character>> owned;
  std::vector<const crowdprof::Character*> characters;
  std::vector<std::string> files;  // per character, as the user or the scene names it
  const crowdprof::Character& first() const { return *characters.front(); }
};

// Loads options.file: a character, or a scene file and its characters. The
// scene's settings fill the options not given on the command line (the
// crowd size, seed, camera, lens, resolution, actions). InputError for a bad
// file (scene files: naming the key).
BenchScene load_bench_scene(BenchCliOptions& options);

void add_bench_options(CLI::App& cmd, BenchCliOptions& options);

// "WxH" as {W, H}, each 1 to 65536; throws UsageError naming --resolution.
std::pair<int, int> parse_resolution(const std::string& value);

// Checks every value that does not depend on the character (UsageError with
// the option's name).
void validate_bench_options(const BenchCliOptions& options);

// Checks every value (UsageError with the option's name) and builds the config.
crowdprof::BenchConfig make_bench_config(const BenchCliOptions& options, const BenchScene& scene);

// The files a bench reads: the character file, or a scene file and every
// character it names (InputError when the scene file is malformed).
std::vector<crowdprof::NamedPath> bench_input_files(const std::string& file);

// UsageError, before any work, when --csv, --json, --trace, --screenshot or --html (and
// the command's `outputs`) cannot be written, when one of them is the character
// file or a character of the scene (or one of the command's `inputs`), or when two of them share a path.
void require_writable_outputs(const BenchCliOptions& options, std::vector<crowdprof::NamedPath> inputs = {},
                              std::vector<crowdprof::NamedPath> outputs = {});

// Opens --backend at --resolution for the config's crowd and points
// config.renderer at its renderer (left null for none). When auto finds no GL,
// says so on stderr and goes on without.
crowdprof::BenchRendering open_bench_rendering(const BenchCliOptions& options, const BenchScene& scene,
                                               crowdprof::BenchConfig& config);

// What a bench runs, resolved from its sources in one visible order: the
// defaults, then the scene file, then a baseline being re-run, then the
// command line. Each source is a SpecLayer of settings by name, as users type
// them ("characters": "40", "culling": "off"); resolve_run_spec applies the
// layers in order and checks every value once, with the table below, so the
// command line, scene files and recorded results cannot drift apart.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "base/modes.h"
#include "result/result.h"

namespace crowdprof {

struct SceneFile;

struct RunSpec {
  std::string file;  // a character (.glb, .gltf, FILE#skin=N) or a scene file (.json)
  size_t characters = 160;
  // shared or random; scene: each character's actions as its scene file says.
  std::string actions = "shared";
  std::string action;  // with shared: the action every copy plays; empty: the first
  uint32_t seed = 1;
  size_t frames = 120, warmup = 10;
  double fps = 60.0;
  double bake_rate = 30.0;  // mode baked: samples per second (animation/bake.h)
  std::string mode = "threaded";
  // Switch overrides by name (base/switch_table.h), as typed.
  std::map<std::string, std::string> switches;
  int threads = 0;  // 0: every core, in parallel modes
  std::string camera = "default";
  double lens = 0;  // focal length in mm; 0: Blender's 35 mm, or the scene's
  std::string backend = "none";
  std::string resolution = "1600x900";
  bool allow_static = false;  // a character without actions stands in its rest pose

  // The mode's switches with the overrides applied; the mode's name, with
  // "+custom" when an override changed it.
  ModeSwitches mode_switches() const;
  std::string mode_name() const;
};

// One setting of a run that is not a switch: its name (as results and scene
// files spell it; the command line as --name, '-' for '_'), its values, help
// and default, and how it is read from text.
struct SettingSpec {
  std::string_view name;
  std::string_view value;  // for help: "N", "FPS", "shared|random"
  std::string_view help;
  std::string_view default_text;  // in help, "" for none
  // Sets the setting in `spec`; returns "" or what is wrong with the text.
  std::string (*set)(RunSpec& spec, std::string_view text);
  // The heading help lists it under: Crowd, Run, View or GPU (the switches
  // are "Mode switches").
  std::string_view group;
};

std::span<const SettingSpec> setting_table();
const SettingSpec* find_setting(std::string_view name);

// Settings by name from one source, as typed.
struct SpecLayer {
  enum class Source { Defaults, SceneFile, Baseline, CommandLine };
  Source source = Source::CommandLine;
  std::string path;  // the scene file or baseline it came from
  std::map<std::string, std::string> values;
  bool has(const std::string& name) const { return values.count(name) > 0; }
};

// What a scene file sets: the crowd size, seed, camera, lens, resolution,
// each character's actions ("actions": "scene"), and the mode, switches and
// threads it names.
SpecLayer scene_layer(const SceneFile& scene);

// What a result recorded (bench --json, a baseline): enough to run it again.
// `file` is the scene file to use (recorded_scene_file). InputError naming
// `path` when it records something crowdprof cannot run.
SpecLayer recorded_layer(const Result& result, const std::string& path, const std::string& file);

// Applies the layers in order over the defaults. Rules that make the order
// mean what users expect:
// - a layer that names a mode brings that mode's switches: switches set by
//   earlier layers are dropped, except that the command line's mode keeps the
//   scene file's switches (they apply over whatever mode runs, as switch
//   options do; a baseline's record replaces them);
// - a layer that names an action without actions asks for shared actions;
// - threads recorded in a scene or baseline apply only when the resolved mode
//   runs in parallel.
// Each value is checked: SettingError for the command line's, InputError
// naming the file for a scene's or baseline's.
RunSpec resolve_run_spec(std::span<const SpecLayer> layers);

// Checks what can be checked without the characters: the values, that the
// switches can run together, that threads apply. Throws as resolve_run_spec.
void validate_run_spec(const RunSpec& spec);

// The spec as `crowdprof bench` arguments (without "bench"): the file, then
// every setting and switch override as its option, so that a process of its
// own runs what the spec resolved to (a scene file's actions stay the scene's).
std::vector<std::string> run_spec_arguments(const RunSpec& spec);

}  // namespace crowdprof

// Scene files: the crowd a user profiles, kept as a file next to the assets
// and in CI instead of a long command line (docs/scenes.md). JSON, read with
// nlohmann-json: already how crowdprof writes its results, so one format and
// one parser for both; a scene is a few lines that people rarely nest.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "asset/character.h"
#include "gen/humanoid.h"
#include "scene/camera.h"
#include "scene/crowd.h"

namespace crowdprof {

// A scene character made by crowdprof's generator rather than read from a
// file ("generate": the options of `crowdprof gen`): a scene that runs from any
// folder with no file beside it.
struct GeneratedCharacter {
  HumanoidOptions humanoid;
  bool draco = false;  // written with KHR_draco_mesh_compression, then decoded as a file's would be
};

// One entry of "characters": a file (or a generated humanoid) and how many
// copies play what.
struct SceneCharacter {
  // As the scene writes it, FILE or FILE#skin=N; for a generated character
  // the gen command that makes the same ("gen --bones 300 --seed 3").
  std::string file;
  std::string path;  // the file relative to the scene file's folder; empty when generated
  std::optional<GeneratedCharacter> generate;
  size_t count = 0;
  ActionChoice actions = ActionChoice::Shared;
  std::string action;                                   // with Shared: the action's name; empty: the first
  std::vector<std::pair<std::string, double>> weights;  // with Weighted: by action name
  // "transitions" and "blend_in": the group's own, over --transitions and
  // --blend-in (a mean of 0 keeps its actions while others change).
  std::optional<TransitionTiming> transitions;
  // "layers": the group's own actions laid over its copies' (each as
  // --anim-layer takes it), over --anim-layer; an empty list: none.
  std::optional<std::vector<AnimLayer>> layers;
};

struct SceneFile {
  std::string path;  // the scene file as given
  std::string hash;  // FNV-1a 64 of its bytes, 16 hex digits
  std::vector<SceneCharacter> characters;
  uint32_t seed = 1;  // random and weighted actions
  CrowdLayout layout;
  std::string camera = "default";  // a --camera spec: default, all, close or EX,EY,EZ,TX,TY,TZ
  Lens lens;
  std::string resolution = "1600x900";
  // "mode": a preset (base/modes.h); empty when the scene names none (the run's
  // default, threaded, or the command line's --mode).
  std::string mode;
  // "switches": overrides of the mode's switches by name (base/switch_table.h),
  // each as users type it ("1/30", "on"; a JSON true or false as on or off, a
  // number as written). They apply over whatever mode runs, as a switch option
  // does: the scene's mode, the command line's --mode, each of compare's --modes.
  std::map<std::string, std::string> switches;
  int threads = 0;        // "threads": workers of a parallel mode; 0: every core
  size_t copies() const;  // in all
};

// True for a path that names a scene file (it ends in .json) rather than a
// character (.gltf, .glb).
bool is_scene_file(const std::string& path);

// Reads and checks a scene file. InputError "<file>: <key>: <problem>" for
// what cannot be read or used: not JSON, unknown keys, wrong types, counts
// below zero or no copies at all, a character file that does not exist, a
// layout or camera value out of range.
SceneFile load_scene_file(const std::string& path);

// The scene as a scene file's text (JSON, two-space indents), which
// load_scene_file reads back as the same scene when the text is saved at
// `destination`: each character file is written relative to the destination's
// folder (absolute when the scene named it so, or when they share no folder
// below the root), a generated character as its
// "generate" entry, every key explicit.
std::string scene_file_text(const SceneFile& scene, const std::string& destination);

// The crowd group of scene character `index`, loaded as `character` (index k
// of the bench's characters): action names resolved. InputError naming the
// scene file and the key when the character has no such action, nor the
// joint or action of a layer: the group's own, and with `switch_layers_run`
// (the run plays the scene's anim_layer switch, not one given over it) the
// switch's.
CrowdGroup scene_group(const SceneFile& scene, size_t index, const Character& character, bool switch_layers_run = true);

// FNV-1a 64 of `bytes` as 16 hex digits.
std::string fnv1a64_hex(std::string_view bytes);

}  // namespace crowdprof

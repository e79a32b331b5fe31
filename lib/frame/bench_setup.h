// From a resolved RunSpec to a bench: the characters it runs on, loaded once,
// and its BenchConfig. The command line never reaches here: values were
// checked by resolve_run_spec, and problems are said by setting name.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asset/character.h"
#include "asset/gltf_loader.h"
#include "frame/crowd_bench.h"
#include "frame/run_spec.h"
#include "base/output_file.h"
#include "scene/scene_file.h"

namespace crowdprof {

// What a bench runs on: the characters loaded, and the scene file when the
// run is of one. Characters keep their addresses (benches point at them).
struct BenchScene {
  std::optional<SceneFile> scene;
  std::vector<std::unique_ptr<Character>> owned;
  std::vector<const Character*> characters;
  std::vector<std::string> files;  // per character, as the user or the scene names it
  // Per character: FNV-1a 64 (hex) of its file's bytes, what diff tells
  // characters apart by (a name says nothing of what changed in the asset).
  std::vector<std::string> content_hashes;
  const Character& first() const { return *characters.front(); }
};

// The asset a scene character names: its file, or the humanoid its "generate"
// entry describes, written as glTF in memory (with Draco when it says so) and
// loaded from those bytes as any file is. `content_hash`, when given, gets
// FNV-1a 64 (hex) of the bytes. InputError for a bad file.
GltfAsset load_scene_asset(const SceneCharacter& character, std::string* content_hash = nullptr);
// Which skin of that asset the character is: FILE#skin=N's, or a generated
// humanoid's only one.
CharacterSpec scene_character_spec(const SceneCharacter& character);

// Loads spec.file: a character, or a scene file and its characters. InputError
// for a bad file (scene files: naming the key); SettingError for actions
// "scene" on a character.
BenchScene load_bench_scene(const RunSpec& spec);

// The layers of a run in their order: `defaults` (a command's own, e.g. render
// draws with auto), the scene file the run is of (the command line's file, else
// the baseline's), the baseline, the command line. InputError for a bad scene
// file.
std::vector<SpecLayer> run_layers(const SpecLayer& command_line, const SpecLayer* baseline = nullptr,
                                  const SpecLayer* defaults = nullptr);

// WxH of a checked resolution.
std::pair<int, int> resolution_size(const std::string& resolution);

// The bench's config: crowd, mode, threads, clock, camera and lens. Throws
// SettingError (a bad camera, an action the character lacks, threads in a
// mode that runs on one) or UsageError (a character without actions, unless
// spec.allow_static).
BenchConfig make_bench_config(const RunSpec& spec, const BenchScene& scene);

// The run's final configuration as a scene file (bench --scene-out): its
// crowd (a mixed scene's counts as scaled to spec.characters, each group's
// actions as they ran), layout, camera, lens, resolution, mode, switches and
// threads, so that `bench` of the scene runs the same crowd and gives the same
// counters and digest. A character file becomes the scene's one character.
SceneFile run_scene_file(const RunSpec& spec, const BenchScene& loaded, const BenchConfig& config);

// The settings of `spec` that a scene file does not hold and that differ from
// their defaults (fps, bake_rate, backend, static): what a run of the scene
// must be given again to replay the same frames.
std::vector<std::string> settings_outside_scene(const RunSpec& spec);

// The files a bench reads: the character file, or a scene file and every
// character it names (InputError when the scene file is malformed).
std::vector<NamedPath> bench_input_files(const std::string& file);

}  // namespace crowdprof

#include "frame/bench_setup.h"

#include <fstream>
#include <iterator>

#include <algorithm>
#include <thread>

#include "base/errors.h"
#include "asset/gltf_container.h"
#include "asset/gltf_loader.h"
#include "asset/vertex_order.h"
#include "gen/gltf_writer.h"
#include "scene/camera.h"

namespace crowdprof {

namespace {
// The hash of a character's file (FILE#skin=N: FILE's), read again after
// the loader took it; empty when it cannot be read.
std::string content_hash(const std::string& spec) {
  const std::string path = spec.substr(0, spec.find("#skin="));
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return in.bad() || bytes.empty() ? std::string() : fnv1a64_hex(bytes);
}

// A character as the file says, then with its vertices in the order skinning
// is quickest in (asset/vertex_order.h): the same triangles, fewer joints a batch.
std::unique_ptr<Character> ordered(Character character) {
  auto owned = std::make_unique<Character>(std::move(character));
  order_vertices_for_skinning(*owned);
  return owned;
}
}  // namespace

CharacterSpec scene_character_spec(const SceneCharacter& c) {
  return c.generate ? CharacterSpec{c.file, -1} : parse_character_spec(c.path);
}

GltfAsset load_scene_asset(const SceneCharacter& c, std::string* hash) {
  if (!c.generate) {
    if (hash) *hash = content_hash(c.path);
    return load_gltf(scene_character_spec(c).file);
  }
  GltfWriteOptions options;
  options.draco = c.generate->draco;
  const std::vector<uint8_t> bytes = encode_gltf(generate_humanoid(c.generate->humanoid), options);
  if (hash) *hash = fnv1a64_hex(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  return load_gltf_from_memory(std::vector<unsigned char>(bytes.begin(), bytes.end()), c.file);
}

BenchScene load_bench_scene(const RunSpec& spec) {
  BenchScene loaded;
  if (!is_scene_file(spec.file)) {
    if (spec.actions == "scene")
      throw SettingError("actions", "scene", spec.file + " is a character, not a scene file");
    loaded.owned.push_back(ordered(load_character(spec.file)));
    loaded.characters.push_back(loaded.owned.back().get());
    loaded.files.push_back(spec.file);
    loaded.content_hashes.push_back(content_hash(spec.file));
    return loaded;
  }
  SceneFile scene = load_scene_file(spec.file);
  for (const SceneCharacter& c : scene.characters) {
    std::string hash;
    GltfAsset asset = load_scene_asset(c, &hash);
    loaded.owned.push_back(ordered(std::move(asset.characters[checked_skin(asset, scene_character_spec(c))])));
    loaded.characters.push_back(loaded.owned.back().get());
    loaded.files.push_back(c.file);
    loaded.content_hashes.push_back(hash);
  }
  loaded.scene = std::move(scene);
  return loaded;
}

std::vector<SpecLayer> run_layers(const SpecLayer& command_line, const SpecLayer* baseline, const SpecLayer* defaults) {
  std::vector<SpecLayer> layers;
  if (defaults) layers.push_back(*defaults);
  std::string file = command_line.has("file")            ? command_line.values.at("file")
                     : baseline && baseline->has("file") ? baseline->values.at("file")
                                                         : std::string();
  if (is_scene_file(file)) layers.push_back(scene_layer(load_scene_file(file)));
  if (baseline) layers.push_back(*baseline);
  layers.push_back(command_line);
  return layers;
}

std::pair<int, int> resolution_size(const std::string& resolution) {
  size_t x = resolution.find('x');
  return {std::stoi(resolution.substr(0, x)), std::stoi(resolution.substr(x + 1))};
}

BenchConfig make_bench_config(const RunSpec& spec, const BenchScene& loaded) {
  validate_run_spec(spec);
  BenchConfig config;
  config.mode = spec.mode_switches();
  config.mode_name = spec.mode_name();
  unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  config.threads = config.mode.parallel ? (spec.threads > 0 ? spec.threads : static_cast<int>(cores)) : 1;
  config.fps = spec.fps;
  config.bake_rate_hz = static_cast<float>(spec.bake_rate);
  config.camera = spec.camera;
  auto [width, height] = resolution_size(spec.resolution);
  config.aspect = static_cast<float>(width) / static_cast<float>(height);
  config.resolution = std::to_string(width) + "x" + std::to_string(height);
  make_camera(spec.camera, Aabb{glm::vec3(0.0f), glm::vec3(1.0f)}, config.aspect);  // throws on a bad camera

  config.crowd.copies = spec.characters;
  config.crowd.seed = spec.seed;
  config.actions_from_scene = spec.actions == "scene";
  if (!config.actions_from_scene)
    config.crowd.actions = spec.actions == "random" ? ActionChoice::Random : ActionChoice::Shared;
  config.files = loaded.files;
  config.content_hashes = loaded.content_hashes;
  for (const Character* character : loaded.characters)
    if (character->actions.empty() && !spec.allow_static)
      throw SettingsUsageError(" has no actions: its crowd would stand still (pass {static} to bench that)",
                               character->name);
  // The index of the action named in each character.
  auto action_index = [&](const Character& character, const std::string& file) {
    std::string names;
    for (size_t a = 0; a < character.actions.size(); ++a) {
      if (character.actions[a].name == spec.action) return static_cast<int>(a);
      names += (names.empty() ? "" : ", ") + character.actions[a].name;
    }
    throw SettingError("action", spec.action,
                       "not one of " + (loaded.scene ? file + "'s" : std::string("the character's")) + " actions (" +
                           (names.empty() ? std::string("it has none") : names) + ")");
  };
  if (!spec.action.empty()) config.crowd.shared_action = action_index(loaded.first(), loaded.files.front());
  if (loaded.scene) {
    const SceneFile& scene = *loaded.scene;
    config.scene_file = scene.path;
    config.scene_hash = scene.hash;
    config.crowd.layout = scene.layout;
    config.lens = scene.lens;
    // The scene's anim_layer switch is its fault only where the run plays it
    // (the command line's, compare's or a baseline's value replaces it).
    const auto ours = scene.switches.find("anim_layer"), run = spec.switches.find("anim_layer");
    const bool scene_layers = ours != scene.switches.end() && run != spec.switches.end() && ours->second == run->second;
    for (size_t k = 0; k < loaded.characters.size(); ++k) {
      CrowdGroup group = scene_group(scene, k, *loaded.characters[k], scene_layers);
      if (!config.actions_from_scene) {
        group.actions = config.crowd.actions;
        group.weights.clear();
        group.shared_action = spec.action.empty() ? 0 : action_index(*loaded.characters[k], loaded.files[k]);
      }
      config.crowd.groups.push_back(std::move(group));
    }
  }
  if (spec.lens != 0) config.lens.focal_mm = static_cast<float>(spec.lens);
  return config;
}

SceneFile run_scene_file(const RunSpec& spec, const BenchScene& loaded, const BenchConfig& config) {
  SceneFile out;
  if (loaded.scene) {
    out.characters = loaded.scene->characters;
    out.lens = loaded.scene->lens;
  } else {
    SceneCharacter c;
    c.file = c.path = spec.file;
    out.characters.push_back(std::move(c));
  }
  // The counts as the run made them (largest remainders), which add up to the
  // crowd's size, so that the scene is run without scaling.
  const std::vector<CrowdGroup> groups = crowd_groups(config.crowd);
  for (size_t k = 0; k < out.characters.size(); ++k) {
    SceneCharacter& c = out.characters[k];
    c.count = groups[k].copies;
    if (!config.actions_from_scene) {
      c.actions = config.crowd.actions;
      c.weights.clear();
      c.action = c.actions == ActionChoice::Shared ? spec.action : std::string();
    }
  }
  out.seed = spec.seed;
  out.layout = config.crowd.layout;
  out.camera = spec.camera;
  out.lens = config.lens;
  out.resolution = config.resolution;
  out.mode = spec.mode;
  out.switches = spec.switches;
  out.threads = spec.threads;
  return out;
}

std::vector<std::string> settings_outside_scene(const RunSpec& spec) {
  const RunSpec defaults;
  std::vector<std::string> names;
  if (spec.fps != defaults.fps) names.push_back("fps");
  if (spec.bake_rate != defaults.bake_rate && spec.mode_switches().skinning == SkinningSite::Baked)
    names.push_back("bake_rate");
  if (spec.backend != defaults.backend) names.push_back("backend");
  if (spec.allow_static) names.push_back("static");
  return names;
}

std::vector<NamedPath> bench_input_files(const std::string& file) {
  // A character's buffers and textures are inputs too (a .gltf's .bin).
  auto add_character = [](std::vector<NamedPath>& inputs, const std::string& what, const std::string& path) {
    inputs.push_back({what, path});
    std::string gltf = path;
    try {
      gltf = parse_character_spec(path).file;  // "hero.gltf#skin=1"
    } catch (const UsageError&) {
    }
    for (const std::string& external : gltf_external_files(gltf)) inputs.push_back({"file read by " + gltf, external});
  };
  std::vector<NamedPath> inputs;
  if (!is_scene_file(file)) {
    add_character(inputs, "character file", file);
    return inputs;
  }
  // The characters a scene names are inputs too: an output on one of them
  // would overwrite a user's character (the scene is read again by the run).
  inputs.push_back({"scene file", file});
  for (const SceneCharacter& character : load_scene_file(file).characters)
    add_character(inputs, "character file of the scene", character.path);
  return inputs;
}

}  // namespace crowdprof

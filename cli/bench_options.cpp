#include "cli/bench_options.h"

#include <cmath>
#include <optional>
#include <iostream>
#include <tuple>
#include <thread>

#include "asset/errors.h"
#include "asset/gltf_loader.h"
#include "output/output_file.h"
#include "render/gl_context.h"
#include "render/gl_features.h"
#include "scene/camera.h"

using crowdprof::UsageError;

void add_bench_options(CLI::App& cmd, BenchCliOptions& o) {
  o.command = &cmd;
  cmd.add_option("file", o.file,
                 "Character (.glb or .gltf, FILE#skin=N to pick a skin, see crowdprof info) or scene file (.json, "
                 "see docs/scenes.md; the options below override what it sets)")
      ->required();
  cmd.add_option("-n,--characters", o.characters,
                 "Copies in the crowd (default: 160, or the scene's; a mixed scene's counts are scaled to it)");
  cmd.add_option("--actions", o.actions,
                 "shared: every copy plays one action in phase (the thesis scene); random: a random action and "
                 "phase per copy (the thesis's -random) (default: shared, or as the scene says)");
  cmd.add_option("--action", o.action, "With --actions shared: the action's name (default: the first)");
  cmd.add_option("--seed", o.seed, "Seed for --actions random (default: 1, or the scene's)");
  cmd.add_option("--frames", o.frames, "Frames measured")->capture_default_str();
  cmd.add_option("--warmup", o.warmup, "Frames run before measuring")->capture_default_str();
  cmd.add_option("--bake-rate", o.bake_rate,
                 "Skinning baked: samples per second each action is baked at (default 30; see docs/modes.md)")
      ->type_name("HZ");
  cmd.add_option("--fps", o.fps,
                 "Simulated clock: frame k shows time k/fps, however long frames take, so runs are reproducible")
      ->capture_default_str();
  cmd.add_option("--mode", o.mode,
                 "Preset of switches: master, culled, threaded, hwskin (the thesis's), buffer, instanced, compute, "
                 "baked (see docs/modes.md)")
      ->capture_default_str();
  cmd.add_option("--threads", o.threads, "Worker threads for parallel modes (default: all cores)");
  cmd.add_option("--camera", o.camera, "default (thesis framing, part of the crowd off-screen), all, close (a few "
                                       "copies at the front), or EX,EY,EZ,TX,TY,TZ (default: default, or the scene's)");
  cmd.add_option("--lens", o.lens,
                 "Focal length in mm on Blender's 32 mm sensor fitted to the larger side (default: 35, Blender's, "
                 "49.1 degrees across; or the scene's)");
  cmd.add_option("--backend", o.backend,
                 "Where frames are drawn: egl (a GPU, else Mesa's surfaceless llvmpipe), osmesa, auto (egl, then "
                 "osmesa, then none) or none (CPU only, nothing drawn)")
      ->capture_default_str();
  cmd.add_option("--resolution", o.resolution,
                 "Frame size WxH in pixels, and the camera's aspect (default: 1600x900, or the scene's)");
  cmd.add_option("--lookups", o.lookups, "Override the mode: string (every channel by path, every frame) or bundled");
  cmd.add_option("--culling", o.culling, "Override the mode: on or off (animation culling, 4.1)");
  cmd.add_option("--pose", o.pose, "Override the mode: shared (one scratch pose, the BGE's) or per-copy");
  cmd.add_option("--parallel", o.parallel, "Override the mode: on or off (oneTBB over copies)");
  cmd.add_option("--skinning", o.skinning, "Override the mode: rasterizer, animations (CPU, counted there), gpu, compute or baked");
  cmd.add_option("--vertex-format", o.vertex_format,
                 "What CPU skinning writes for the GPU: float (32-bit positions and normals, 24 bytes a vertex) or "
                 "packed (16-bit positions in the character's box, 10:10:10:2 normals, 10 bytes)");
  cmd.add_option("--palettes", o.palettes,
                 "Override the mode: uniforms (a uniform array per draw, 128 bones at most) or buffer (one shader "
                 "storage buffer, no bone limit); for skinning on the GPU");
  cmd.add_option("--draw", o.draw,
                 "Override the mode: per-copy (a draw call per copy) or instanced (one per character kind; needs "
                 "--palettes buffer)");
  cmd.add_option("--share", o.share,
                 "Override the mode: on or off (animation sharing: copies in the same action and time share one pose "
                 "and one skinned mesh)");
  cmd.add_option("--share-quantum", o.share_quantum,
                 "With --share on: snap each copy's time to a multiple of this many seconds (e.g. 1/30 or 0.05) so "
                 "copies fall into shared states; 0: exact times");
  cmd.add_option("--update-lod", o.update_lod,
                 "Override the mode: on or off (update-rate LOD: copies updated every 1, 2, 4 or 8 frames by size on "
                 "screen, holding their pose between)");
  cmd.add_option("--lod-thresholds", o.lod_thresholds,
                 "A,B,C: shares of the screen's height at which a copy is updated every frame (>= A), every 2nd "
                 "(>= B), every 4th (>= C), else every 8th (default: 0.25,0.125,0.0625)");
  cmd.add_option("--anim-budget", o.anim_budget,
                 "Milliseconds: keep the Animations category's p95 at or under this by updating the copies smallest "
                 "on screen less often (at least every 64 frames); 0: no budget");
  cmd.add_flag("--static", o.allow_static, "Accept a character without actions: a crowd in its rest pose");
  cmd.add_flag("-q,--quiet", o.quiet, "Print nothing on stdout (files still written)");
}

namespace {

bool parse_on_off(const std::string& value, const char* option) {
  if (value == "on") return true;
  if (value == "off") return false;
  throw UsageError(std::string(option) + " '" + value + "': expected on or off");
}

template <typename Enum>
Enum parse_choice(const std::string& value, const char* option,
                  std::initializer_list<std::pair<const char*, Enum>> choices) {
  std::string names;
  for (const auto& [name, e] : choices) {
    if (value == name) return e;
    names += names.empty() ? name : std::string(", ") + name;
  }
  throw UsageError(std::string(option) + " '" + value + "': expected one of " + names);
}

// A number as the whole text (no trailing junk), or nullopt.
std::optional<double> parse_number(const std::string& text) {
  if (text.empty() || text.size() > 32) return std::nullopt;
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Seconds, as a decimal or a fraction 1/N.
double parse_share_quantum(const std::string& text) {
  std::optional<double> value;
  size_t slash = text.find('/');
  if (slash == std::string::npos) {
    value = parse_number(text);
  } else {
    std::optional<double> top = parse_number(text.substr(0, slash)), bottom = parse_number(text.substr(slash + 1));
    if (top && bottom && *bottom > 0) value = *top / *bottom;
  }
  if (!value || *value < 0 || *value > 10)
    throw UsageError("--share-quantum '" + text + "': expected seconds from 0 to 10, e.g. 1/30 or 0.05");
  return *value;
}

crowdprof::LodThresholds parse_lod_thresholds(const std::string& text) {
  std::optional<double> v[3];
  size_t first = text.find(','), second = first == std::string::npos ? first : text.find(',', first + 1);
  if (second != std::string::npos && text.find(',', second + 1) == std::string::npos) {
    v[0] = parse_number(text.substr(0, first));
    v[1] = parse_number(text.substr(first + 1, second - first - 1));
    v[2] = parse_number(text.substr(second + 1));
  }
  if (!v[0] || !v[1] || !v[2] || !(*v[0] <= 1 && *v[0] >= *v[1] && *v[1] >= *v[2] && *v[2] >= 0))
    throw UsageError("--lod-thresholds '" + text +
                     "': expected three shares of the screen's height A,B,C with 1 >= A >= B >= C >= 0");
  return {static_cast<float>(*v[0]), static_cast<float>(*v[1]), static_cast<float>(*v[2])};
}

double parse_anim_budget(const std::string& text) {
  std::optional<double> value = parse_number(text);
  if (!value || *value < 0 || *value > 10000)
    throw UsageError("--anim-budget '" + text + "': expected milliseconds from 0 (no budget) to 10000");
  return *value;
}

}  // namespace

std::pair<int, int> parse_resolution(const std::string& value) {
  int size[2] = {0, 0};
  size_t x = value.find('x');
  bool ok = x != std::string::npos && x > 0 && x + 1 < value.size();
  for (int i = 0; ok && i < 2; ++i) {
    std::string part = i == 0 ? value.substr(0, x) : value.substr(x + 1);
    ok = part.size() <= 6 && part.find_first_not_of("0123456789") == std::string::npos;
    if (ok) size[i] = std::stoi(part);
  }
  if (!ok) throw UsageError("--resolution '" + value + "': expected WIDTHxHEIGHT, e.g. 1600x900");
  if (size[0] < 1 || size[1] < 1 || size[0] > 65536 || size[1] > 65536)
    throw UsageError("--resolution '" + value + "': width and height must be 1 to 65536 pixels");
  return {size[0], size[1]};
}

static crowdprof::BenchConfig config_from_options(const BenchCliOptions& o) {
  using namespace crowdprof;
  if (o.characters < 1) throw UsageError("-n " + std::to_string(o.characters) + ": a crowd needs at least 1 copy");
  if (o.characters > 10'000'000) throw UsageError("-n " + std::to_string(o.characters) + ": at most 10,000,000 copies");
  if (o.frames < 1) throw UsageError("--frames " + std::to_string(o.frames) + ": at least 1 frame is measured");
  if (o.warmup < 0) throw UsageError("--warmup " + std::to_string(o.warmup) + ": cannot be negative");
  if (o.frames > 10'000'000 || o.warmup > 10'000'000) throw UsageError("--frames/--warmup: at most 10,000,000");
  if (!(o.fps > 0) || !std::isfinite(o.fps) || o.fps > 100000)
    throw UsageError("--fps " + std::to_string(o.fps) + ": expected a rate between 0 and 100000");
  if (o.seed < 0 || o.seed > 0xffffffffLL) throw UsageError("--seed: expected 0 to 4294967295");
  if (o.lens != 0 && !(o.lens >= 1 && o.lens <= 5000))
    throw UsageError("--lens " + std::to_string(o.lens) + ": expected a focal length of 1 to 5000 mm");
  if (!o.actions.empty() && o.actions != "shared" && o.actions != "random" && o.actions != "scene")
    throw UsageError("--actions '" + o.actions + "': expected one of shared, random");
  if (!parse_backend(o.backend))
    throw UsageError("--backend '" + o.backend + "': expected auto, egl, osmesa or none");
  auto [width, height] = parse_resolution(o.resolution);

  BenchConfig config;
  const ModePreset* preset = find_mode(o.mode);
  if (!preset) throw UsageError("--mode '" + o.mode + "': expected one of " + mode_names());
  config.mode = preset->switches;
  config.mode_name = std::string(preset->name);
  if (!o.lookups.empty())
    config.mode.lookups = parse_choice<Lookups>(o.lookups, "--lookups",
                                                {{"string", Lookups::PerFrameString}, {"bundled", Lookups::Bundled}});
  if (!o.culling.empty()) config.mode.animation_culling = parse_on_off(o.culling, "--culling");
  if (!o.pose.empty())
    config.mode.pose = parse_choice<PoseStorage>(o.pose, "--pose",
                                                 {{"shared", PoseStorage::SharedScratch}, {"per-copy", PoseStorage::PerCopy}});
  if (!o.parallel.empty()) config.mode.parallel = parse_on_off(o.parallel, "--parallel");
  if (!o.skinning.empty())
    config.mode.skinning = parse_choice<SkinningSite>(
        o.skinning, "--skinning",
        {{"rasterizer", SkinningSite::CpuInRasterizer}, {"animations", SkinningSite::CpuInAnimations}, {"gpu", SkinningSite::Gpu},
         {"compute", SkinningSite::Compute}, {"baked", SkinningSite::Baked}});
  if (!o.vertex_format.empty())
    config.mode.vertex_format = parse_choice<VertexFormat>(
        o.vertex_format, "--vertex-format", {{"float", VertexFormat::Float}, {"packed", VertexFormat::Packed}});
  if (!o.palettes.empty())
    config.mode.palettes = parse_choice<PaletteStorage>(
        o.palettes, "--palettes", {{"uniforms", PaletteStorage::Uniforms}, {"buffer", PaletteStorage::Buffer}});
  if (!o.draw.empty())
    config.mode.draw =
        parse_choice<DrawMethod>(o.draw, "--draw", {{"per-copy", DrawMethod::PerCopy}, {"instanced", DrawMethod::Instanced}});
  if (!o.share.empty()) config.mode.share_poses = parse_on_off(o.share, "--share");
  if (!o.share_quantum.empty()) config.mode.share_quantum_s = parse_share_quantum(o.share_quantum);
  if (!o.update_lod.empty()) config.mode.update_lod = parse_on_off(o.update_lod, "--update-lod");
  if (!o.lod_thresholds.empty()) config.mode.lod = parse_lod_thresholds(o.lod_thresholds);
  if (!o.anim_budget.empty()) config.mode.anim_budget_ms = parse_anim_budget(o.anim_budget);
  // An override that repeats the preset leaves it the preset.
  if (config.mode != preset->switches) config.mode_name += "+custom";

  if (o.threads != kThreadsUnset && (o.threads < 1 || o.threads > 1024))
    throw UsageError("--threads " + std::to_string(o.threads) + ": expected 1 to 1024");
  unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (o.threads > 1 && !config.mode.parallel)
    throw UsageError("--threads " + std::to_string(o.threads) + ": mode " + config.mode_name +
                     " runs on one thread; threads apply to parallel modes (threaded, hwskin, or --parallel on)");
  config.threads = config.mode.parallel ? (o.threads > 0 ? static_cast<int>(o.threads) : static_cast<int>(cores)) : 1;

  config.fps = o.fps;
  if (!(o.bake_rate > 0) || !(o.bake_rate <= 10000))
    throw UsageError("--bake-rate " + std::to_string(o.bake_rate) + ": expected 0 to 10000 samples per second");
  config.bake_rate_hz = static_cast<float>(o.bake_rate);
  config.camera = o.camera;
  config.aspect = static_cast<float>(width) / static_cast<float>(height);
  config.resolution = std::to_string(width) + "x" + std::to_string(height);
  make_camera(o.camera, Aabb{glm::vec3(0.0f), glm::vec3(1.0f)}, config.aspect);  // throws on a bad --camera
  if (o.lens != 0) config.lens.focal_mm = static_cast<float>(o.lens);
  return config;
}

void validate_bench_options(const BenchCliOptions& options) { config_from_options(options); }

BenchScene load_bench_scene(BenchCliOptions& o) {
  using namespace crowdprof;
  BenchScene loaded;
  if (!is_scene_file(o.file)) {
    loaded.owned.push_back(std::make_unique<Character>(load_character(o.file)));
    loaded.characters.push_back(loaded.owned.back().get());
    loaded.files.push_back(o.file);
    if (o.actions == "scene") throw UsageError("--actions scene: " + o.file + " is a character, not a scene file");
    return loaded;
  }
  SceneFile scene = load_scene_file(o.file);
  for (const SceneCharacter& c : scene.characters) {
    loaded.owned.push_back(std::make_unique<Character>(load_character(c.path)));
    loaded.characters.push_back(loaded.owned.back().get());
    loaded.files.push_back(c.file);
  }
  if (!o.given("--characters")) o.characters = static_cast<long long>(scene.copies());
  if (!o.given("--seed")) o.seed = scene.seed;
  if (!o.given("--camera")) o.camera = scene.camera;
  if (!o.given("--resolution")) o.resolution = scene.resolution;
  if (!o.given("--lens")) o.lens = scene.lens.focal_mm;
  if (!o.given("--actions") && !o.given("--action")) o.actions = "scene";
  loaded.scene = std::move(scene);
  return loaded;
}

crowdprof::BenchConfig make_bench_config(const BenchCliOptions& o, const BenchScene& loaded) {
  using namespace crowdprof;
  BenchConfig config = config_from_options(o);
  config.crowd.copies = static_cast<size_t>(o.characters);
  config.crowd.seed = static_cast<uint32_t>(o.seed);
  std::string actions = o.actions.empty() ? "shared" : o.actions;
  config.actions_from_scene = actions == "scene";
  if (!config.actions_from_scene)
    config.crowd.actions = parse_choice<ActionChoice>(actions, "--actions",
                                                      {{"shared", ActionChoice::Shared}, {"random", ActionChoice::Random}});
  config.files = loaded.files;
  for (const Character* character : loaded.characters)
    if (character->actions.empty() && !o.allow_static)
      throw UsageError(character->name + " has no actions: its crowd would stand still (pass --static to bench that)");
  // --action NAME: the index of that action in each character.
  auto action_index = [&](const Character& character, const std::string& file) {
    std::string names;
    for (size_t a = 0; a < character.actions.size(); ++a) {
      if (character.actions[a].name == o.action) return static_cast<int>(a);
      names += (names.empty() ? "" : ", ") + character.actions[a].name;
    }
    throw UsageError("--action '" + o.action + "': " + (loaded.scene ? file + "'s" : std::string("the character's")) +
                     " actions are " + (names.empty() ? std::string("none") : names));
  };
  if (!o.action.empty()) config.crowd.shared_action = action_index(loaded.first(), loaded.files.front());
  if (loaded.scene) {
    const SceneFile& scene = *loaded.scene;
    config.scene_file = scene.path;
    config.scene_hash = scene.hash;
    config.crowd.layout = scene.layout;
    config.lens = scene.lens;
    for (size_t k = 0; k < loaded.characters.size(); ++k) {
      CrowdGroup group = scene_group(scene, k, *loaded.characters[k]);
      if (!config.actions_from_scene) {
        group.actions = config.crowd.actions;
        group.weights.clear();
        group.shared_action = o.action.empty() ? 0 : action_index(*loaded.characters[k], loaded.files[k]);
      }
      config.crowd.groups.push_back(std::move(group));
    }
  }
  if (o.lens != 0) config.lens.focal_mm = static_cast<float>(o.lens);
  return config;
}

std::vector<crowdprof::NamedPath> bench_input_files(const std::string& file) {
  if (!crowdprof::is_scene_file(file)) return {{"character file", file}};
  // The characters a scene names are inputs too: an output on one of them
  // would overwrite a user's character (the scene is read again by the run).
  std::vector<crowdprof::NamedPath> inputs = {{"scene file", file}};
  for (const crowdprof::SceneCharacter& character : crowdprof::load_scene_file(file).characters)
    inputs.push_back({"character file of the scene", character.path});
  return inputs;
}

void require_writable_outputs(const BenchCliOptions& o, std::vector<crowdprof::NamedPath> inputs,
                              std::vector<crowdprof::NamedPath> outputs) {
  std::vector<crowdprof::NamedPath> files = bench_input_files(o.file);
  inputs.insert(inputs.begin(), files.begin(), files.end());
  std::vector<std::pair<crowdprof::NamedPath, const char*>> mine = {
      {{"--csv", o.csv}, "CSV"}, {{"--json", o.json}, "JSON"}, {{"--trace", o.trace}, "trace"},
      {{"--screenshot", o.screenshot}, "PNG"}, {{"--html", o.html}, "HTML"}};
  std::vector<crowdprof::NamedPath> all;
  for (const auto& [path, what] : mine) all.push_back(path);
  all.insert(all.end(), outputs.begin(), outputs.end());
  crowdprof::require_distinct_outputs(inputs, all);
  for (const auto& [path, what] : mine)
    if (!path.path.empty()) crowdprof::require_writable(path.path, what);
}

crowdprof::BenchRendering open_bench_rendering(const BenchCliOptions& o, const BenchScene& scene,
                                               crowdprof::BenchConfig& config) {
  using namespace crowdprof;
  RendererConfig renderer;
  std::tie(renderer.width, renderer.height) = parse_resolution(o.resolution);
  renderer.hide_features = gl_hide_from_environment();
  std::string warning;
  BenchRendering rendering = open_rendering(*parse_backend(o.backend), scene.characters, config.crowd.copies, renderer, &warning);
  if (!warning.empty()) std::cerr << "crowdprof: warning: " << warning << "\n";
  config.renderer = rendering.renderer.get();
  return rendering;
}

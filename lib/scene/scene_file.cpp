#include "animation/binding.h"
#include "animation/layering.h"
#include "scene/scene_file.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "base/input_file.h"
#include "base/modes.h"
#include "base/switch_table.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// Reports problems as "<file>: <key>: <problem>", the key as a path such as
// characters[1].count.
struct SceneReader {
  std::string file;

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(file, key.empty() ? problem : key + ": " + problem);  // empty: the whole file
  }

  void only_keys(const json& object, const std::string& key, std::initializer_list<const char*> allowed) const {
    if (!object.is_object()) fail(key, "expected an object, got " + type_of(object));
    for (const auto& [name, value] : object.items()) {
      bool known = false;
      std::string list;
      for (const char* a : allowed) {
        known = known || name == a;
        list += (list.empty() ? "" : ", ") + std::string(a);
      }
      if (!known) fail(key.empty() ? name : key + "." + name, "unknown key (expected one of " + list + ")");
    }
  }

  static std::string type_of(const json& value) {
    if (value.is_number_integer() || value.is_number_unsigned()) return "a whole number";
    if (value.is_number()) return "a number";
    const std::string name = value.type_name();
    return (name == "array" || name == "object" ? "an " : "a ") + name;
  }

  std::string text(const json& value, const std::string& key) const {
    if (!value.is_string()) fail(key, "expected a string, got " + type_of(value));
    return value.get<std::string>();
  }

  double number(const json& value, const std::string& key, double min, double max) const {
    if (!value.is_number()) fail(key, "expected a number, got " + type_of(value));
    double v = value.get<double>();
    if (!std::isfinite(v) || v < min || v > max) {
      char range[96];
      std::snprintf(range, sizeof range, "%g is out of range (%g to %g)", v, min, max);
      fail(key, range);
    }
    return v;
  }

  long long whole(const json& value, const std::string& key, long long min, long long max) const {
    if (!value.is_number_integer() && !value.is_number_unsigned())
      fail(key, "expected a whole number, got " + type_of(value));
    if (value.is_number_unsigned() && value.get<uint64_t>() > static_cast<uint64_t>(max))
      fail(key, std::to_string(value.get<uint64_t>()) + " is more than " + std::to_string(max));
    long long v = value.get<long long>();
    if (v < min || v > max)
      fail(key, std::to_string(v) + " is out of range (" + std::to_string(min) + " to " + std::to_string(max) + ")");
    return v;
  }

  glm::vec3 point(const json& value, const std::string& key) const {
    if (!value.is_array() || value.size() != 3) fail(key, "expected [x, y, z] in metres");
    glm::vec3 p;
    for (int i = 0; i < 3; ++i) p[i] = static_cast<float>(number(value[static_cast<size_t>(i)], key, -1e6, 1e6));
    return p;
  }
};

// "generate": {"bones", "vertices", "seed", "lods", "actions", "draco"}, each
// optional, with gen's defaults and ranges.
GeneratedCharacter generated_character(const SceneReader& r, const json& value, const std::string& key) {
  r.only_keys(value, key, {"bones", "vertices", "seed", "lods", "actions", "draco"});
  GeneratedCharacter g;
  HumanoidOptions& h = g.humanoid;
  if (value.contains("bones"))
    h.bones = static_cast<int>(r.whole(value["bones"], key + ".bones", kHumanoidMinBones, kHumanoidMaxBones));
  if (value.contains("vertices"))
    h.vertices =
        static_cast<int>(r.whole(value["vertices"], key + ".vertices", kHumanoidMinVertices, kHumanoidMaxVertices));
  if (value.contains("seed")) h.seed = static_cast<uint32_t>(r.whole(value["seed"], key + ".seed", 0, 0xffffffffLL));
  if (value.contains("lods")) h.lod_levels = static_cast<int>(r.whole(value["lods"], key + ".lods", 0, 3));
  if (value.contains("actions")) {
    const std::string actions = r.text(value["actions"], key + ".actions");
    if (actions == "locomotion")
      h.actions = HumanoidActions::Locomotion;
    else if (actions != "default")
      r.fail(key + ".actions", "'" + actions + "': expected default or locomotion");
  }
  if (value.contains("draco")) {
    if (!value["draco"].is_boolean())
      r.fail(key + ".draco", "expected true or false, got " + SceneReader::type_of(value["draco"]));
    g.draco = value["draco"].get<bool>();
  }
  return g;
}

// The `crowdprof gen` options that make the same character, those that differ
// from gen's defaults: how results and messages name it.
std::string gen_command(const GeneratedCharacter& g) {
  const HumanoidOptions& h = g.humanoid;
  const HumanoidOptions defaults;
  std::string out = "gen";
  if (h.bones != defaults.bones) out += " --bones " + std::to_string(h.bones);
  if (h.vertices != defaults.vertices) out += " --vertices " + std::to_string(h.vertices);
  if (h.seed != defaults.seed) out += " --seed " + std::to_string(h.seed);
  if (h.lod_levels != defaults.lod_levels) out += " --lods " + std::to_string(h.lod_levels);
  if (h.actions == HumanoidActions::Locomotion) out += " --actions locomotion";
  if (g.draco) out += " --draco";
  return out;
}

std::string folder_of(const std::string& path) {
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::string() : parent.string() + "/";
}

// A group's "transitions" (0: it keeps its actions; else seconds, as
// --transitions takes) and "blend_in" (as --blend-in, its default too; at most
// half of the group's transitions, so that its fades never overlap).
// A group's "layers": a list of layers, each as --anim-layer takes one
// ("action=wave,mask=spine"); at most kMaxAnimLayers (base/anim_layers.h).
std::vector<AnimLayer> group_layers(const SceneReader& r, const json& list, const std::string& key) {
  if (!list.is_array())
    r.fail(key, "expected a list of layers such as [\"action=wave,mask=spine\"], got " + SceneReader::type_of(list));
  std::string joined;
  for (size_t i = 0; i < list.size(); ++i)
    joined += (i ? "\n" : "") + r.text(list[i], key + "[" + std::to_string(i) + "]");
  std::vector<AnimLayer> layers;
  if (std::string why = parse_anim_layers(joined, &layers); !why.empty()) r.fail(key, why);
  return layers;
}

TransitionTiming group_transitions(const SceneReader& r, const json& entry, const std::string& key) {
  TransitionTiming t;
  t.mean_s = r.number(entry["transitions"], key + ".transitions", 0, 3600);
  if (t.mean_s > 0 && t.mean_s < 0.05)
    r.fail(key + ".transitions", "expected 0 (no changes) or seconds from 0.05 to 3600");
  const bool given = entry.contains("blend_in");
  t.blend_in_s = given ? r.number(entry["blend_in"], key + ".blend_in", 0, 3600) : ModeSwitches{}.blend_in_s;
  if (t.mean_s > 0 && t.blend_in_s > 0.5 * t.mean_s) {
    char why[160];
    std::snprintf(why, sizeof why, "%s%g s is more than half of transitions (%g s): fades would overlap",
                  given ? "" : "the default ", t.blend_in_s, t.mean_s);
    r.fail(key + ".blend_in", why);
  }
  return t;
}

// "mode", "switches" and "threads": how the scene runs. Each switch is
// checked as the command line's option is (a JSON true or false reads as on or
// off, a number as written), and the scene's switches over its mode (threaded
// when it names none) must be able to run together.
void scene_mode_and_switches(const SceneReader& r, const json& doc, SceneFile& scene) {
  if (doc.contains("mode")) {
    scene.mode = r.text(doc["mode"], "mode");
    if (!find_mode(scene.mode)) r.fail("mode", "'" + scene.mode + "': expected one of " + mode_names());
  }
  if (doc.contains("threads")) scene.threads = static_cast<int>(r.whole(doc["threads"], "threads", 1, 1024));
  if (!doc.contains("switches")) return;
  const json& switches = doc["switches"];
  if (!switches.is_object())
    r.fail("switches",
           "expected an object of switches by name, e.g. {\"culling\": \"on\"}, got " + SceneReader::type_of(switches));
  ModeSwitches s = find_mode(scene.mode.empty() ? "threaded" : scene.mode)->switches;
  for (const auto& [name, value] : switches.items()) {
    const std::string key = "switches." + name;
    const SwitchSpec* spec = find_switch(name);
    if (!spec) r.fail(key, "no such switch (the switches are " + switch_names() + ")");
    if (!value.is_string() && !value.is_boolean() && !value.is_number())
      r.fail(key, "expected a value as the option " + option_spelling(name) + " takes (" + std::string(spec->value) +
                      "), got " + SceneReader::type_of(value));
    const std::string text = switch_text(value);
    if (std::string problem = spec->set(s, text); !problem.empty()) r.fail(key, "'" + text + "': " + problem);
    scene.switches[name] = text;
  }
  if (SettingText conflict = conflicts(s); !conflict.empty())
    r.fail("switches", "with mode " + (scene.mode.empty() ? std::string("threaded") : scene.mode) + ": " +
                           conflict.str([](std::string_view name) { return "switches." + std::string(name); }));
}

}  // namespace

size_t SceneFile::copies() const {
  size_t n = 0;
  for (const SceneCharacter& c : characters) n += c.count;
  return n;
}

bool is_scene_file(const std::string& path) {
  std::string lower = path;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower.size() > 5 && lower.ends_with(".json");
}

std::string fnv1a64_hex(std::string_view bytes) {
  uint64_t hash = 0xcbf29ce484222325ull;
  for (unsigned char c : bytes) hash = (hash ^ c) * 0x100000001b3ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

SceneFile load_scene_file(const std::string& path) {
  SceneReader r{path};
  std::ifstream in(path, std::ios::binary);
  std::error_code missing;
  if (!in) throw InputError(path, std::filesystem::exists(path, missing) ? "cannot be read" : "no such file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string bytes = buffer.str();
  SceneFile scene;
  scene.path = path;
  scene.hash = fnv1a64_hex(bytes);
  // The parser every input file shares: a number past a double (1e400) or
  // absurd nesting is refused like broken JSON, naming the file.
  json doc = parse_json_input(path, bytes, /*unique_keys=*/true);
  if (doc.is_object() && doc.contains("crowdprof"))
    throw InputError(path, "this is a crowdprof result, not a scene file: use report, or check --result");
  r.only_keys(doc, "", {"characters", "seed", "layout", "camera", "resolution", "mode", "switches", "threads"});

  if (!doc.contains("characters")) r.fail("characters", "missing: a scene needs at least one character");
  const json& characters = doc["characters"];
  if (!characters.is_array() || characters.empty())
    r.fail("characters", "expected a list of at least one character, got " + SceneReader::type_of(characters));
  if (characters.size() > 1000) r.fail("characters", "at most 1,000 characters");
  std::string folder = folder_of(path);
  for (size_t i = 0; i < characters.size(); ++i) {
    std::string key = "characters[" + std::to_string(i) + "]";
    const json& entry = characters[i];
    r.only_keys(entry, key, {"file", "generate", "count", "actions", "action", "transitions", "blend_in", "layers"});
    SceneCharacter c;
    if (entry.contains("file") && entry.contains("generate"))
      r.fail(key + ".generate", "with file: give one of the two");
    if (!entry.contains("file") && !entry.contains("generate")) r.fail(key + ".file", "missing (or generate)");
    if (entry.contains("generate")) {
      c.generate = generated_character(r, entry["generate"], key + ".generate");
      c.file = gen_command(*c.generate);
    } else {
      c.file = r.text(entry["file"], key + ".file");
      std::string name = c.file.substr(0, c.file.find('#'));
      if (name.empty()) r.fail(key + ".file", "empty");
      c.path = std::filesystem::path(name).is_absolute() ? c.file : folder + c.file;
      std::string on_disk = c.path.substr(0, c.path.find('#'));
      // With an error code: a path too long for the system is a missing file, not an exception.
      std::error_code unreadable;
      if (!std::filesystem::is_regular_file(on_disk, unreadable))
        r.fail(key + ".file", "no such file '" + c.file + "' (looked for " + on_disk + ")");
    }
    if (!entry.contains("count")) r.fail(key + ".count", "missing: how many copies of this character");
    c.count = static_cast<size_t>(r.whole(entry["count"], key + ".count", 0, 10'000'000));
    if (entry.contains("actions")) {
      const json& actions = entry["actions"];
      if (actions.is_string()) {
        std::string choice = actions.get<std::string>();
        if (choice == "shared")
          c.actions = ActionChoice::Shared;
        else if (choice == "random")
          c.actions = ActionChoice::Random;
        else
          r.fail(key + ".actions", "'" + choice + "': expected shared, random, or an object of weights by action name");
      } else if (actions.is_object()) {
        c.actions = ActionChoice::Weighted;
        double total = 0;
        for (const auto& [action, weight] : actions.items()) {
          double w = r.number(weight, key + ".actions." + action, 0, 1e9);
          c.weights.emplace_back(action, w);
          total += w;
        }
        if (!(total > 0)) r.fail(key + ".actions", "weights must not all be zero");
      } else {
        r.fail(key + ".actions",
               "expected shared, random, or an object of weights by action name, got " + SceneReader::type_of(actions));
      }
    }
    if (entry.contains("action")) {
      if (c.actions != ActionChoice::Shared) r.fail(key + ".action", "only with \"actions\": \"shared\"");
      c.action = r.text(entry["action"], key + ".action");
    }
    if (entry.contains("blend_in") && !entry.contains("transitions"))
      r.fail(key + ".blend_in", "only with \"transitions\" in the same entry");
    if (entry.contains("transitions")) c.transitions = group_transitions(r, entry, key);
    if (entry.contains("layers")) c.layers = group_layers(r, entry["layers"], key + ".layers");
    scene.characters.push_back(std::move(c));
  }
  if (scene.copies() == 0) r.fail("characters", "no copies at all: every count is 0");
  if (scene.copies() > 10'000'000) r.fail("characters", "at most 10,000,000 copies in all");

  if (doc.contains("seed")) scene.seed = static_cast<uint32_t>(r.whole(doc["seed"], "seed", 0, 0xffffffffLL));

  if (doc.contains("layout")) {
    const json& layout = doc["layout"];
    r.only_keys(layout, "layout", {"type", "spacing", "rows", "jitter", "seed"});
    if (layout.contains("type") && r.text(layout["type"], "layout.type") != "grid")
      r.fail("layout.type", "'" + layout["type"].get<std::string>() + "': the only layout is grid");
    if (layout.contains("spacing") && !(layout["spacing"].is_string() && layout["spacing"] == "auto"))
      scene.layout.spacing = static_cast<float>(r.number(layout["spacing"], "layout.spacing", 0.001, 1e4));
    if (layout.contains("rows") && !(layout["rows"].is_string() && layout["rows"] == "auto"))
      scene.layout.rows = static_cast<size_t>(r.whole(layout["rows"], "layout.rows", 1, 10'000'000));
    if (layout.contains("jitter"))
      scene.layout.jitter = static_cast<float>(r.number(layout["jitter"], "layout.jitter", 0, 1e4));
    if (layout.contains("seed"))
      scene.layout.jitter_seed = static_cast<uint32_t>(r.whole(layout["seed"], "layout.seed", 0, 0xffffffffLL));
  }

  if (doc.contains("camera")) {
    const json& camera = doc["camera"];
    r.only_keys(camera, "camera",
                {"view", "eye", "target", "lens_mm", "sensor_width_mm", "sensor_height_mm", "sensor_fit"});
    bool placed = camera.contains("eye") || camera.contains("target");
    if (camera.contains("view")) {
      if (placed) r.fail("camera.view", "give either a view or an eye and a target, not both");
      scene.camera = r.text(camera["view"], "camera.view");
      if (scene.camera != "default" && scene.camera != "all" && scene.camera != "close")
        r.fail("camera.view", "'" + scene.camera + "': expected default, all or close");
    }
    if (placed) {
      if (!camera.contains("eye") || !camera.contains("target"))
        r.fail(camera.contains("eye") ? "camera.target" : "camera.eye",
               "missing: an eye needs a target and the other way round");
      glm::vec3 eye = r.point(camera["eye"], "camera.eye"), target = r.point(camera["target"], "camera.target");
      if (glm::length(eye - target) < 1e-6f) r.fail("camera.target", "the same point as the eye");
      char spec[256];
      std::snprintf(spec, sizeof spec, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", eye.x, eye.y, eye.z, target.x, target.y,
                    target.z);
      scene.camera = spec;
    }
    if (camera.contains("lens_mm"))
      scene.lens.focal_mm = static_cast<float>(r.number(camera["lens_mm"], "camera.lens_mm", 1, 5000));
    if (camera.contains("sensor_width_mm"))
      scene.lens.sensor_width_mm =
          static_cast<float>(r.number(camera["sensor_width_mm"], "camera.sensor_width_mm", 1, 1000));
    if (camera.contains("sensor_height_mm"))
      scene.lens.sensor_height_mm =
          static_cast<float>(r.number(camera["sensor_height_mm"], "camera.sensor_height_mm", 1, 1000));
    if (camera.contains("sensor_fit")) {
      std::string fit = r.text(camera["sensor_fit"], "camera.sensor_fit");
      std::optional<SensorFit> parsed = parse_sensor_fit(fit);
      if (!parsed) r.fail("camera.sensor_fit", "'" + fit + "': expected auto, horizontal or vertical");
      scene.lens.fit = *parsed;
    }
  }

  if (doc.contains("resolution")) {
    scene.resolution = r.text(doc["resolution"], "resolution");
    size_t x = scene.resolution.find('x');
    bool ok = x != std::string::npos && x > 0 && x + 1 < scene.resolution.size() && x <= 5 &&
              scene.resolution.size() - x - 1 <= 5 &&
              scene.resolution.find_first_not_of("0123456789x") == std::string::npos &&
              scene.resolution.find('x', x + 1) == std::string::npos;
    if (ok) {
      int w = std::stoi(scene.resolution.substr(0, x)), h = std::stoi(scene.resolution.substr(x + 1));
      ok = w >= 1 && h >= 1 && w <= 65536 && h <= 65536;
    }
    if (!ok) r.fail("resolution", "'" + scene.resolution + "': expected WIDTHxHEIGHT, each 1 to 65536, e.g. 1600x900");
  }
  scene_mode_and_switches(r, doc, scene);
  return scene;
}

namespace {

using ordered = nlohmann::ordered_json;

// A float as the shortest decimal that reads back as it (0.3, not
// 0.30000001192092896), the float's exact value when a double read of that
// decimal would round to another float.
double float_number(float f) {
  char text[32];
  auto [end, ec] = std::to_chars(text, text + sizeof text, f);
  if (ec != std::errc()) return f;
  double d = 0;
  std::from_chars(text, end, d);
  return static_cast<float>(d) == f ? d : static_cast<double>(f);
}

// A generated character's "generate" entry: the values that differ from gen's
// defaults.
ordered generate_entry(const GeneratedCharacter& g) {
  const HumanoidOptions& h = g.humanoid;
  const HumanoidOptions defaults;
  ordered entry = ordered::object();
  if (h.bones != defaults.bones) entry["bones"] = h.bones;
  if (h.vertices != defaults.vertices) entry["vertices"] = h.vertices;
  if (h.seed != defaults.seed) entry["seed"] = h.seed;
  if (h.lod_levels != defaults.lod_levels) entry["lods"] = h.lod_levels;
  if (h.actions == HumanoidActions::Locomotion) entry["actions"] = "locomotion";
  if (g.draco) entry["draco"] = true;
  return entry;
}

// A character file as seen from `folder` (absolute): relative, unless the
// scene named it by an absolute path or the two share no folder but the root;
// FILE#skin=N keeps its skin.
std::string file_from(const SceneCharacter& c, const std::filesystem::path& folder) {
  if (std::filesystem::path(c.file.substr(0, c.file.find('#'))).is_absolute()) return c.file;
  const size_t hash = c.path.find('#');
  const std::string on_disk = c.path.substr(0, hash), skin = hash == std::string::npos ? "" : c.path.substr(hash);
  std::filesystem::path file(on_disk);
  const std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
  // Relative only when the two share a folder below the root (not ../../usr/...).
  auto a = absolute.begin(), f = folder.begin();
  size_t shared = 0;
  for (; a != absolute.end() && f != folder.end() && *a == *f; ++a, ++f) ++shared;
  const std::filesystem::path relative = absolute.lexically_relative(folder);
  return (shared < 2 || relative.empty() ? absolute : relative).generic_string() + skin;
}

ordered camera_entry(const SceneFile& scene) {
  ordered camera = ordered::object();
  if (scene.camera == "default" || scene.camera == "all" || scene.camera == "close") {
    camera["view"] = scene.camera;
  } else {
    // EX,EY,EZ,TX,TY,TZ, read as make_camera reads it: floats, written exactly.
    float v[6] = {};
    const char* p = scene.camera.data();
    const char* end = p + scene.camera.size();
    for (float& value : v) {
      auto [next, ec] = std::from_chars(p, end, value);
      if (ec != std::errc()) throw InputError(scene.path, "camera: '" + scene.camera + "' is not EX,EY,EZ,TX,TY,TZ");
      p = next < end ? next + 1 : next;
    }
    camera["eye"] = {float_number(v[0]), float_number(v[1]), float_number(v[2])};
    camera["target"] = {float_number(v[3]), float_number(v[4]), float_number(v[5])};
  }
  camera["lens_mm"] = float_number(scene.lens.focal_mm);
  camera["sensor_width_mm"] = float_number(scene.lens.sensor_width_mm);
  camera["sensor_height_mm"] = float_number(scene.lens.sensor_height_mm);
  camera["sensor_fit"] = std::string(to_string(scene.lens.fit));
  return camera;
}

}  // namespace

std::string scene_file_text(const SceneFile& scene, const std::string& destination) {
  std::filesystem::path folder = std::filesystem::path(destination).parent_path();
  folder = std::filesystem::absolute(folder.empty() ? std::filesystem::path(".") : folder).lexically_normal();
  ordered doc = ordered::object();
  ordered characters = ordered::array();
  for (const SceneCharacter& c : scene.characters) {
    ordered entry = ordered::object();
    if (c.generate)
      entry["generate"] = generate_entry(*c.generate);
    else
      entry["file"] = file_from(c, folder);
    entry["count"] = c.count;
    if (c.actions == ActionChoice::Weighted) {
      ordered weights = ordered::object();
      for (const auto& [action, weight] : c.weights) weights[action] = weight;
      entry["actions"] = weights;
    } else {
      entry["actions"] = c.actions == ActionChoice::Random ? "random" : "shared";
    }
    if (c.actions == ActionChoice::Shared && !c.action.empty()) entry["action"] = c.action;
    if (c.transitions) {
      entry["transitions"] = c.transitions->mean_s;
      entry["blend_in"] = c.transitions->blend_in_s;
    }
    if (c.layers) {
      ordered layers = ordered::array();
      for (const AnimLayer& layer : *c.layers) layers.push_back(anim_layers_text({layer}));
      entry["layers"] = std::move(layers);
    }
    characters.push_back(std::move(entry));
  }
  doc["characters"] = std::move(characters);
  doc["seed"] = scene.seed;
  ordered layout = {{"type", "grid"}};
  layout["spacing"] = scene.layout.spacing > 0 ? ordered(float_number(scene.layout.spacing)) : ordered("auto");
  layout["rows"] = scene.layout.rows > 0 ? ordered(scene.layout.rows) : ordered("auto");
  layout["jitter"] = float_number(scene.layout.jitter);
  layout["seed"] = scene.layout.jitter_seed;
  doc["layout"] = std::move(layout);
  doc["camera"] = camera_entry(scene);
  doc["resolution"] = scene.resolution;
  if (!scene.mode.empty()) doc["mode"] = scene.mode;
  if (!scene.switches.empty()) {
    ordered switches = ordered::object();
    for (const SwitchSpec& spec : switch_table())  // in the table's order
      if (auto it = scene.switches.find(std::string(spec.name)); it != scene.switches.end())
        switches[it->first] = it->second;
    doc["switches"] = std::move(switches);
  }
  if (scene.threads > 0) doc["threads"] = scene.threads;
  return doc.dump(2) + "\n";
}

CrowdGroup scene_group(const SceneFile& scene, size_t index, const Character& character, bool switch_layers_run) {
  const SceneCharacter& c = scene.characters[index];
  std::string key = "characters[" + std::to_string(index) + "]";
  CrowdGroup group;
  group.character = index;
  group.copies = c.count;
  group.actions = c.actions;
  group.transitions = c.transitions;
  group.layers = c.layers;
  auto find = [&](const std::string& name, const std::string& at) {
    std::string names;
    for (size_t a = 0; a < character.actions.size(); ++a) {
      if (character.actions[a].name == name) return a;
      names += (names.empty() ? "" : ", ") + character.actions[a].name;
    }
    throw InputError(scene.path, at + ": " + c.file + " has no action '" + name + "' (it has " +
                                     (names.empty() ? std::string("none") : names) + ")");
  };
  if (character.actions.empty() && c.actions != ActionChoice::Shared)
    throw InputError(scene.path, key + ".actions: " + c.file + " has no actions to choose from");
  if (c.actions == ActionChoice::Shared && !c.action.empty())
    group.shared_action = static_cast<int>(find(c.action, key + ".action"));
  if (c.actions == ActionChoice::Weighted) {
    group.weights.assign(character.actions.size(), 0.0);
    for (const auto& [name, weight] : c.weights) group.weights[find(name, key + ".actions." + name)] += weight;
  }
  if (c.layers && !c.layers->empty()) {
    // Named actions and joints checked here, where the error can name the key.
    std::vector<ActionBindings> bindings;
    for (const Action& action : character.actions) bindings.push_back(bind_action(character.skeleton, action));
    CharacterLayers resolved;
    if (std::string why = resolve_layers(character, bindings, *c.layers, &resolved); !why.empty())
      throw InputError(scene.path, key + ".layers: " + why);
  }
  // The scene's own anim_layer switch too: its fault, not the command line's.
  if (auto it = scene.switches.find("anim_layer"); switch_layers_run && it != scene.switches.end() && !group.layers) {
    ModeSwitches parsed;
    if (find_switch("anim_layer")->set(parsed, it->second).empty() && !parsed.anim_layers.empty()) {
      std::vector<ActionBindings> bindings;
      for (const Action& action : character.actions) bindings.push_back(bind_action(character.skeleton, action));
      CharacterLayers resolved;
      if (std::string why = resolve_layers(character, bindings, parsed.anim_layers, &resolved); !why.empty())
        throw InputError(scene.path, "switches.anim_layer: " + why);
    }
  }
  return group;
}

}  // namespace crowdprof

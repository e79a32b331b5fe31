#include "frame/run_spec.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <thread>

#include "base/switch_table.h"
#include "base/number_text.h"
#include "base/backend_choice.h"
#include "scene/camera.h"
#include "scene/scene_file.h"

namespace crowdprof {

namespace {

using nlohmann::json;

std::optional<long long> parse_whole(std::string_view text) {
  size_t digits = text.starts_with('-') ? 1 : 0;
  if (text.size() <= digits || text.size() > 19 + digits ||
      text.find_first_not_of("0123456789", digits) != std::string_view::npos)
    return std::nullopt;
  return std::stoll(std::string(text));
}

// Sets a whole-number setting within [min, max]; `below` is said for values
// under min.
template <typename T>
std::string set_whole(T& field, std::string_view text, long long min, long long max, const char* below,
                      const char* above) {
  std::optional<long long> value = parse_whole(text);
  if (!value) return std::string("expected a whole number (") + below + ")";
  if (*value < min) return below;
  if (*value > max) return above;
  field = static_cast<T>(*value);
  return {};
}

std::string set_text(std::string& field, std::string_view text) {
  field = std::string(text);
  return {};
}

std::string set_resolution(RunSpec& spec, std::string_view value) {
  int size[2] = {0, 0};
  size_t x = value.find('x');
  bool ok = x != std::string_view::npos && x > 0 && x + 1 < value.size();
  for (int i = 0; ok && i < 2; ++i) {
    std::string_view part = i == 0 ? value.substr(0, x) : value.substr(x + 1);
    ok = part.size() <= 6 && part.find_first_not_of("0123456789") == std::string_view::npos;
    if (ok) size[i] = std::stoi(std::string(part));
  }
  if (!ok) return "expected WIDTHxHEIGHT, e.g. 1600x900";
  if (size[0] < 1 || size[1] < 1 || size[0] > 65536 || size[1] > 65536)
    return "width and height must be 1 to 65536 pixels";
  spec.resolution = std::string(value);
  return {};
}

const std::array kSettings = {
    SettingSpec{"characters", "N", "Copies in the crowd (a mixed scene's counts are scaled to it)",
                "160, or the scene's",
                [](RunSpec& s, std::string_view t) {
                  return set_whole(s.characters, t, 1, 10'000'000, "a crowd needs at least 1 copy",
                                   "at most 10,000,000 copies");
                },
                "Crowd"},
    SettingSpec{"actions", "shared|random",
                "shared: every copy plays one action in phase (the thesis scene); random: a random action and phase "
                "per copy (the thesis's -random)",
                "shared, or as the scene says",
                [](RunSpec& s, std::string_view t) -> std::string {
                  if (t != "shared" && t != "random" && t != "scene") return "expected one of shared, random";
                  s.actions = std::string(t);
                  return {};
                },
                "Crowd"},
    SettingSpec{"action", "NAME", "With shared actions: the action's name", "the first",
                [](RunSpec& s, std::string_view t) { return set_text(s.action, t); }, "Crowd"},
    SettingSpec{"seed", "N", "Seed for random actions", "1, or the scene's",
                [](RunSpec& s, std::string_view t) {
                  return set_whole(s.seed, t, 0, 0xffffffffLL, "expected 0 to 4294967295", "expected 0 to 4294967295");
                },
                "Crowd"},
    SettingSpec{"frames", "N", "Frames measured", "120",
                [](RunSpec& s, std::string_view t) {
                  return set_whole(s.frames, t, 1, 10'000'000, "at least 1 frame is measured", "at most 10,000,000");
                },
                "Run"},
    SettingSpec{"warmup", "N", "Frames run before measuring", "10",
                [](RunSpec& s, std::string_view t) {
                  return set_whole(s.warmup, t, 0, 10'000'000, "cannot be negative", "at most 10,000,000");
                },
                "Run"},
    SettingSpec{"fps", "FPS",
                "Simulated clock: frame k shows time k/fps, however long frames take, so runs are reproducible", "60",
                [](RunSpec& s, std::string_view t) -> std::string {
                  std::optional<double> v = parse_number(t);
                  if (!v) return "expected a number (a rate between 0 and 100000)";
                  if (!(*v > 0) || *v > 100000) return "expected frames a second above 0, at most 100000";
                  s.fps = *v;
                  return {};
                },
                "Run"},
    SettingSpec{"bake_rate", "HZ", "Skinning baked: samples per second each action is baked at (see docs/modes.md)",
                "30",
                [](RunSpec& s, std::string_view t) -> std::string {
                  std::optional<double> v = parse_number(t);
                  if (!v) return "expected a number (more than 0, at most 10000 samples per second)";
                  if (!(*v > 0) || !(*v <= 10000)) return "expected more than 0 and at most 10000 samples per second";
                  s.bake_rate = *v;
                  return {};
                },
                "Run"},
    SettingSpec{"mode", "MODE", "Preset of switches (the first four are the thesis's; see docs/modes.md)", "threaded",
                [](RunSpec& s, std::string_view t) -> std::string {
                  if (!find_mode(t)) return "expected one of " + mode_names();
                  s.mode = std::string(t);
                  return {};
                },
                "Run"},
    SettingSpec{"threads", "N", "Worker threads for parallel modes", "all cores",
                [](RunSpec& s, std::string_view t) {
                  return set_whole(s.threads, t, 1, 1024, "expected 1 to 1024", "expected 1 to 1024");
                },
                "Run"},
    SettingSpec{"camera", "VIEW",
                "default (thesis framing, part of the crowd off-screen), all, close (a few copies at the front), or "
                "EX,EY,EZ,TX,TY,TZ",
                "default, or the scene's",
                [](RunSpec& s, std::string_view t) -> std::string {
                  try {
                    make_camera(std::string(t), Aabb{glm::vec3(0.0f), glm::vec3(1.0f)}, 16.0f / 9.0f);
                  } catch (const SettingError& e) {
                    return e.why;
                  }
                  s.camera = std::string(t);
                  return {};
                },
                "Drawing"},
    SettingSpec{"lens", "MM",
                "Focal length in mm on Blender's 32 mm sensor fitted to the larger side (35 is Blender's, 49.1 "
                "degrees across; 0 keeps 35, or the scene's)",
                "35, or the scene's",
                [](RunSpec& s, std::string_view t) -> std::string {
                  std::optional<double> v = parse_number(t);
                  if (!v) return "expected a number (a focal length of 1 to 5000 mm)";
                  if (*v != 0 && !(*v >= 1 && *v <= 5000)) return "expected a focal length of 1 to 5000 mm";
                  s.lens = *v;
                  return {};
                },
                "Drawing"},
    SettingSpec{"backend", "auto|egl|osmesa|none",
                "Where frames are drawn: egl (a GPU, else Mesa's surfaceless llvmpipe), osmesa, auto (egl, then "
                "osmesa, then none) or none (CPU only, nothing drawn)",
                "none",
                [](RunSpec& s, std::string_view t) -> std::string {
                  if (!parse_backend(t)) return "expected auto, egl, osmesa or none";
                  s.backend = std::string(t);
                  return {};
                },
                "Drawing"},
    SettingSpec{"resolution", "WxH", "Frame size in pixels, and the camera's aspect", "1600x900, or the scene's",
                set_resolution, "Drawing"},
    SettingSpec{"static", "on|off", "Accept a character without actions: a crowd in its rest pose", "off",
                [](RunSpec& s, std::string_view t) -> std::string {
                  if (t != "on" && t != "off") return "expected on or off";
                  s.allow_static = t == "on";
                  return {};
                },
                "Crowd"},
};

// A bad value from `layer`: the command line's is a usage error, a file's an
// input error naming it.
[[noreturn]] void bad_value(const SpecLayer& layer, const std::string& name, const std::string& text,
                            const std::string& problem) {
  if (layer.source == SpecLayer::Source::CommandLine || layer.source == SpecLayer::Source::Defaults)
    throw SettingError(name, text, problem);
  std::string what = layer.source == SpecLayer::Source::Baseline ? "records a run that crowdprof cannot make: " : "";
  throw InputError(layer.path, what + name + " '" + text + "': " + problem);
}

std::string text_of(const json& value) {
  return switch_text(value);
}

}  // namespace

ModeSwitches RunSpec::mode_switches() const {
  const ModePreset* preset = find_mode(mode);
  ModeSwitches s = preset ? preset->switches : ModeSwitches{};
  for (const auto& [name, text] : switches)
    if (const SwitchSpec* spec = find_switch(name)) spec->set(s, text);  // checked by resolve_run_spec
  return s;
}

std::string RunSpec::mode_name() const {
  const ModePreset* preset = find_mode(mode);
  // An override that repeats the preset leaves it the preset.
  return preset && mode_switches() != preset->switches ? mode + "+custom" : mode;
}

std::span<const SettingSpec> setting_table() {
  return kSettings;
}

const SettingSpec* find_setting(std::string_view name) {
  for (const SettingSpec& spec : kSettings)
    if (spec.name == name) return &spec;
  return nullptr;
}

SpecLayer scene_layer(const SceneFile& scene) {
  SpecLayer layer{SpecLayer::Source::SceneFile, scene.path, {}};
  layer.values["characters"] = std::to_string(scene.copies());
  layer.values["seed"] = std::to_string(scene.seed);
  layer.values["camera"] = scene.camera;
  layer.values["resolution"] = scene.resolution;
  layer.values["lens"] = switch_text(json(static_cast<double>(scene.lens.focal_mm)));
  layer.values["actions"] = "scene";
  if (!scene.mode.empty()) layer.values["mode"] = scene.mode;
  for (const auto& [name, text] : scene.switches) layer.values[name] = text;
  if (scene.threads > 0) layer.values["threads"] = std::to_string(scene.threads);
  return layer;
}

SpecLayer recorded_layer(const Result& result, const std::string& path, const std::string& file) {
  SpecLayer layer{SpecLayer::Source::Baseline, path, {}};
  auto& v = layer.values;
  const RunDescription& run = result.run;
  v["file"] = file;
  v["characters"] = std::to_string(run.characters);
  v["frames"] = std::to_string(result.frames());
  v["warmup"] = std::to_string(run.warmup);
  v["fps"] = switch_text(json(run.fps));
  v["actions"] = run.action_choice;
  if (!run.action.empty() && run.action_choice == "shared") v["action"] = run.action;
  v["seed"] = std::to_string(run.seed);
  v["camera"] = run.camera;
  if (!run.resolution.empty()) v["resolution"] = run.resolution;
  std::string mode = run.mode;
  if (mode.ends_with("+custom")) mode.resize(mode.size() - 7);
  v["mode"] = mode;
  // The switches as a result records them (those that differ from the plain
  // ones, and those always recorded), and those that differ from the mode's
  // preset: a result leaves out a switch at its plain value, which the
  // preset may not hold (mode shared with share off).
  const json switches = switches_to_json(run.switches);
  const ModePreset* preset = find_mode(mode);
  for (const SwitchSpec& spec : switch_table())
    if (switches.contains(spec.name))
      v[std::string(spec.name)] = text_of(switches[spec.name]);
    else if (preset && spec.get(run.switches) != spec.get(preset->switches))
      v[std::string(spec.name)] = text_of(spec.get(run.switches));
  // Threads were chosen only for a parallel run; a run on one thread records 1.
  if (run.switches.parallel) v["threads"] = std::to_string(run.threads);
  v["backend"] = run.backend;
  v["static"] = run.actions == 0 ? "on" : "off";
  if (run.lens && run.lens->focal_mm != 0) v["lens"] = switch_text(json(run.lens->focal_mm));
  return layer;
}

RunSpec resolve_run_spec(std::span<const SpecLayer> layers) {
  RunSpec spec;
  const SpecLayer* threads_from = nullptr;
  std::map<std::string, std::string> scene_switches;  // a scene file's own
  for (const SpecLayer& layer : layers) {
    if (layer.has("mode")) {
      // The command line's --mode keeps the scene file's switches (as it keeps
      // its own switch options); a scene's or a baseline's mode brings a whole
      // configuration.
      if (layer.source == SpecLayer::Source::CommandLine)
        spec.switches = scene_switches;
      else
        spec.switches.clear();
    }
    // An action over actions chosen below (a scene's, a baseline's random) means shared.
    if (layer.has("action") && !layer.has("actions")) spec.actions = "shared";
    // One action for every copy and a choice per copy, said together: not one silently dropped.
    if (layer.has("action") && layer.has("actions") && layer.values.at("actions") != "shared")
      bad_value(layer, "action", layer.values.at("action"),
                "plays one action for every copy, which --actions " + layer.values.at("actions") +
                    " does not (it gives each copy its own): give one or the other");
    for (const auto& [name, text] : layer.values) {
      if (name == "file") {
        spec.file = text;
      } else if (const SwitchSpec* sw = find_switch(name)) {
        ModeSwitches scratch;
        if (std::string problem = sw->set(scratch, text); !problem.empty()) bad_value(layer, name, text, problem);
        spec.switches[name] = text;
        if (layer.source == SpecLayer::Source::SceneFile) scene_switches[name] = text;
      } else if (const SettingSpec* setting = find_setting(name)) {
        if (std::string problem = setting->set(spec, text); !problem.empty()) bad_value(layer, name, text, problem);
        if (name == "threads") threads_from = &layer;
      } else {
        bad_value(layer, name, text, "no such setting");
      }
    }
  }
  if (threads_from && threads_from->source != SpecLayer::Source::CommandLine && !spec.mode_switches().parallel)
    spec.threads = 0;
  return spec;
}

void validate_run_spec(const RunSpec& spec) {
  ModeSwitches s = spec.mode_switches();
  if (spec.threads > 1 && !s.parallel)
    throw SettingError("threads", std::to_string(spec.threads),
                       "mode " + spec.mode_name() +
                           " runs on one thread; threads apply to parallel modes (threaded, hwskin, or parallel on)");
}

}  // namespace crowdprof

namespace crowdprof {

std::vector<std::string> run_spec_arguments(const RunSpec& spec) {
  auto number = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return std::string(text);
  };
  std::vector<std::string> args = {spec.file,
                                   "--characters",
                                   std::to_string(spec.characters),
                                   "--seed",
                                   std::to_string(spec.seed),
                                   "--frames",
                                   std::to_string(spec.frames),
                                   "--warmup",
                                   std::to_string(spec.warmup),
                                   "--fps",
                                   number(spec.fps),
                                   "--bake-rate",
                                   number(spec.bake_rate),
                                   "--mode",
                                   spec.mode,
                                   "--camera",
                                   spec.camera,
                                   "--backend",
                                   spec.backend,
                                   "--resolution",
                                   spec.resolution};
  if (spec.actions != "scene") args.insert(args.end(), {"--actions", spec.actions});
  if (!spec.action.empty()) args.insert(args.end(), {"--action", spec.action});
  if (spec.threads > 0) args.insert(args.end(), {"--threads", std::to_string(spec.threads)});
  if (spec.lens > 0) args.insert(args.end(), {"--lens", number(spec.lens)});
  // Of a scene file, every switch: the process reads the scene's switches
  // again, which the spec may have replaced (a baseline's record).
  if (is_scene_file(spec.file)) {
    const ModeSwitches s = spec.mode_switches();
    for (const SwitchSpec& sw : switch_table()) args.insert(args.end(), {option_spelling(sw.name), switch_text(sw, s)});
  } else {
    for (const auto& [name, text] : spec.switches) args.insert(args.end(), {option_spelling(name), text});
  }
  if (spec.allow_static) args.push_back("--static");
  return args;
}

}  // namespace crowdprof

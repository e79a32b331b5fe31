#include "cli/bench_options.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <iostream>
#include <thread>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "cli/installed_data.h"
#include "base/output_file.h"
#include "base/switch_table.h"
#include "scene/camera.h"

using crowdprof::UsageError;

std::string option_name(const std::string& setting) {
  if (setting == "characters") return "-n/--characters";
  return crowdprof::option_spelling(setting);
}

std::string as_options(const crowdprof::SettingText& text) {
  return text.str([](std::string_view setting) { return option_name(std::string(setting)); });
}

void add_bench_options(CLI::App& cmd, BenchCliOptions& o) {
  using namespace crowdprof;
  o.command = &cmd;
  cmd.add_option("file", o.typed["file"],
                 "Character (.glb or .gltf, FILE#skin=N to pick a skin, see crowdprof info) or scene file (.json, "
                 "see docs/scenes.md; the options below override what it sets)")
      ->required();
  for (const SettingSpec& setting : setting_table()) {
    std::string name(setting.name), help(setting.help);
    std::string default_text(setting.default_text);
    if (o.defaults.has(name)) default_text = o.defaults.values.at(name);  // the command's own
    if (!default_text.empty()) help += " (default: " + default_text + ")";
    if (name == "static") {
      cmd.add_flag("--static", o.allow_static, help)->group(std::string(setting.group));
      continue;
    }
    if (name == "mode") help = "Preset of switches: " + mode_names() + help.substr(help.find(" ("));
    std::string flags = name == "characters" ? "-n,--characters" : option_spelling(name);
    cmd.add_option(flags, o.typed[name], help)
        ->type_name(std::string(setting.value))
        ->group(std::string(setting.group));
  }
  for (const SwitchSpec& spec : switch_table()) {
    std::string name(spec.name);
    CLI::Option* option =
        cmd.add_option(option_spelling(name), o.typed[name],
                       std::string(spec.help) + " (overrides the mode's: " + preset_values(spec) + ")")
            ->type_name(std::string(spec.value))
            ->group(kModeSwitchesGroup);
    if (spec.repeatable) option->multi_option_policy(CLI::MultiOptionPolicy::Join);
  }
  cmd.add_flag("-q,--quiet", o.quiet, "Print nothing on stdout (files still written)")->group(kOutputsGroup);
}

void group_options(CLI::App& cmd, const std::string& group, std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (CLI::Option* option = cmd.get_option_no_throw(name)) option->group(group);
}

void group_outputs(CLI::App& cmd) {
  group_options(cmd, kOutputsGroup,
                {"--csv", "--summary-csv", "--json", "--gbench-json", "--trace", "--screenshot", "--svg", "--html",
                 "--junit", "--markdown", "--scene-out", "--quiet"});
}

crowdprof::SpecLayer command_line_layer(const BenchCliOptions& o) {
  crowdprof::SpecLayer layer;
  for (const auto& [name, text] : o.typed) {
    std::string option = name == "file"         ? "file"
                         : name == "characters" ? "--characters"
                                                : crowdprof::option_spelling(name);
    const CLI::Option* given = o.command ? o.command->get_option_no_throw(option) : nullptr;
    if (given && given->count() > 0) layer.values[name] = name == "file" ? with_installed_data(text) : text;
  }
  if (o.allow_static) layer.values["static"] = "on";
  return layer;
}

void resolve_bench_spec(BenchCliOptions& o, const crowdprof::SpecLayer* baseline) {
  o.spec = crowdprof::resolve_run_spec(crowdprof::run_layers(command_line_layer(o), baseline, &o.defaults));
}

void require_writable_outputs(const BenchCliOptions& o, const std::vector<crowdprof::NamedPath>& inputs) {
  std::vector<crowdprof::NamedPath> all = crowdprof::bench_input_files(o.spec.file);
  all.insert(all.end(), inputs.begin(), inputs.end());
  o.outputs.files().require_usable(all);
}

namespace {
struct OutputKind {
  const char* option;  // in messages: "--json X.glb is the input file"
  const char* what;    // in messages: "cannot write SVG file ..."
  const char* flags;   // as declared, when more than the option
};
// By OutputOption.
constexpr OutputKind kOutputKinds[] = {
    {"--csv", "CSV", nullptr},           {"--json", "JSON", nullptr},        {"--trace", "trace", nullptr},
    {"--screenshot", "PNG", nullptr},    {"--html", "HTML", nullptr},        {"--svg", "SVG", nullptr},
    {"--summary-csv", "CSV", nullptr},   {"--gbench-json", "JSON", nullptr}, {"--junit", "JUnit XML", nullptr},
    {"--markdown", "Markdown", nullptr}, {"-o", "PNG", "-o,--output"},       {"-o", "HTML", "-o,--output"},
    {"--scene-out", "scene", nullptr}};
}  // namespace

CLI::Option* DeclaredOutputs::declare(CLI::App& cmd, OutputOption output, std::string& path, const std::string& help) {
  declared_.emplace_back(output, &path);
  const OutputKind& kind = kOutputKinds[static_cast<size_t>(output)];
  return cmd.add_option(kind.flags ? kind.flags : kind.option, path, help)->type_name("FILE")->group(kOutputsGroup);
}

crowdprof::OutputFiles DeclaredOutputs::files() const {
  auto declared = declared_;
  std::stable_sort(declared.begin(), declared.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  crowdprof::OutputFiles files;
  for (const auto& [output, path] : declared) {
    const OutputKind& kind = kOutputKinds[static_cast<size_t>(output)];
    files.add(kind.option, kind.what, *path);
  }
  return files;
}

crowdprof::BenchRendering open_bench_rendering(const BenchCliOptions& o, const crowdprof::BenchScene& scene,
                                               crowdprof::BenchConfig& config) {
  using namespace crowdprof;
  SettingText warning;
  BenchRendering rendering = open_bench_rendering(o.spec, scene, config, &warning);
  if (!warning.empty()) std::cerr << "crowdprof: warning: " << as_options(warning) << "\n";
  return rendering;
}

// --scene-out: the configuration that ran, as a scene file bench runs as is;
// a note names what the scene cannot hold.
void write_scene_out(const std::string& path, const crowdprof::RunSpec& spec, const crowdprof::BenchScene& scene,
                     const crowdprof::BenchConfig& config) {
  using namespace crowdprof;
  write_file(path, "scene", scene_file_text(run_scene_file(spec, scene, config), path));
  std::string outside;
  for (const std::string& name : settings_outside_scene(spec))
    outside += (outside.empty() ? "" : ", ") + option_name(name);
  if (!outside.empty())
    std::cerr << "crowdprof: note: " << path << " holds the crowd, view, mode and switches, not " << outside
              << ": give them again to run the same frames\n";
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> items;
  for (size_t at = 0; !text.empty() && at <= text.size();) {
    const size_t comma = std::min(text.find(',', at), text.size());
    items.push_back(text.substr(at, comma - at));
    at = comma + 1;
  }
  return items;
}

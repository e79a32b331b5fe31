#include <iostream>

#include "asset/asset_report.h"
#include "base/errors.h"
#include "cli/commands.h"
#include "cli/help_format.h"
#include "cli/installed_data.h"
#include "frame/bench_setup.h"
#include "scene/scene_file.h"

namespace {

// One asset as info describes it: the whole of it, or the skin `spec` picks.
nlohmann::json describe(const crowdprof::GltfAsset& asset, const crowdprof::CharacterSpec& spec, bool json,
                        std::ostream& out) {
  int only = spec.skin < 0 ? -1 : static_cast<int>(crowdprof::checked_skin(asset, spec));
  if (json) return crowdprof::describe_asset(asset, only);
  out << crowdprof::format_asset(asset, only);
  return {};
}

}  // namespace

void add_info_command(CLI::App& app, std::function<int()>& run) {
  auto* cmd = app.add_subcommand("info",
                                 "Describe the characters in a glTF/GLB file: joints, vertices, "
                                 "influences, fix-ups, actions, Draco, memory");
  cmd->footer("Examples:\n  crowdprof info scenes/humanoid.glb");
  static std::string file;
  static bool json = false;
  cmd->add_option("file", file,
                  "glTF (.gltf) or binary glTF (.glb) file; FILE#skin=N describes only skin N; a scene file (.json): "
                  "each of its characters")
      ->required();
  // info's one option of its own is with the options every command takes.
  cmd->add_flag("--json", json, "Print the same as JSON, for scripts")->group(kGeneralGroup);
  cmd->callback([&run] {
    run = [] {
      file = with_installed_data(file);
      if (!crowdprof::is_scene_file(file)) {
        const crowdprof::CharacterSpec spec = crowdprof::parse_character_spec(file);
        nlohmann::json doc = describe(crowdprof::load_gltf(spec.file), spec, json, std::cout);
        if (json) std::cout << doc.dump(2) << "\n";
        return int(crowdprof::kExitOk);
      }
      // A scene file: each of its characters, with its count.
      crowdprof::SceneFile scene = crowdprof::load_scene_file(file);
      nlohmann::json doc = {{"scene_file", file}, {"scene_hash", scene.hash}, {"characters", nlohmann::json::array()}};
      for (size_t i = 0; i < scene.characters.size(); ++i) {
        const crowdprof::SceneCharacter& c = scene.characters[i];
        if (!json)
          std::cout << (i ? "\n" : "") << file << ": characters[" << i << "]: " << c.file << ", " << c.count
                    << (c.count == 1 ? " copy\n" : " copies\n");
        nlohmann::json info =
            describe(crowdprof::load_scene_asset(c), crowdprof::scene_character_spec(c), json, std::cout);
        if (json) doc["characters"].push_back({{"file", c.file}, {"count", c.count}, {"info", info}});
      }
      if (json) std::cout << doc.dump(2) << "\n";
      return int(crowdprof::kExitOk);
    };
  });
}

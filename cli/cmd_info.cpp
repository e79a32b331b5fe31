#include <iostream>

#include "asset/asset_report.h"
#include "asset/errors.h"
#include "cli/commands.h"

void add_info_command(CLI::App& app, std::function<int()>& run) {
  auto* cmd = app.add_subcommand("info", "Describe the characters in a glTF/GLB file: joints, vertices, "
                                         "influences, fix-ups, actions, Draco, memory");
  static std::string file;
  static bool json = false;
  cmd->add_option("file", file, "glTF (.gltf) or binary glTF (.glb) file; FILE#skin=N describes only skin N")
      ->required();
  cmd->add_flag("--json", json, "Print the same as JSON, for scripts");
  cmd->callback([&run] {
    run = [] {
      crowdprof::CharacterSpec spec = crowdprof::parse_character_spec(file);
      crowdprof::GltfAsset asset = crowdprof::load_gltf(spec.file);
      int only = spec.skin < 0 ? -1 : static_cast<int>(crowdprof::checked_skin(asset, spec));
      if (json) std::cout << crowdprof::describe_asset(asset, only).dump(2) << "\n";
      else std::cout << crowdprof::format_asset(asset, only);
      return int(crowdprof::kExitOk);
    };
  });
}

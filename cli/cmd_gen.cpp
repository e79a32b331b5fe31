#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>

#include "base/errors.h"
#include "gen/gltf_writer.h"
#include "gen/humanoid.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "base/output_file.h"

namespace {

struct GenArgs {
  std::string output;
  crowdprof::HumanoidOptions humanoid;
  bool draco = false;
  bool gltf = false;
  std::string actions = "default";
};

int gen(const GenArgs& args) {
  std::string ext = std::filesystem::path(args.output).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (args.gltf && ext == ".glb")
    throw crowdprof::UsageError("--gltf writes JSON glTF, but " + args.output + " ends in .glb");
  crowdprof::GltfWriteOptions options;
  options.binary = !(args.gltf || ext == ".gltf");
  options.draco = args.draco;
  crowdprof::HumanoidOptions humanoid = args.humanoid;
  if (args.actions == "locomotion") humanoid.actions = crowdprof::HumanoidActions::Locomotion;
  crowdprof::Character character = crowdprof::generate_humanoid(humanoid);
  crowdprof::write_gltf(character, args.output, options);
  if (crowdprof::is_standard_output(args.output)) return crowdprof::kExitOk;  // stdout holds the file alone
  std::error_code error;                                                      // a pipe has no size
  uintmax_t bytes = std::filesystem::file_size(args.output, error);
  if (static_cast<long long>(character.file_lods.size()) < humanoid.lod_levels)
    std::cerr << "crowdprof: note: --lods " << humanoid.lod_levels << " asked, " << character.file_lods.size()
              << " written: a level keeps at least 500 vertices and fewer than the level above\n";
  std::cout << "wrote " << args.output << ": " << character.skeleton.joint_count() << " joints, "
            << character.mesh.vertex_count() << " vertices, " << character.actions.size() << " actions"
            << (character.file_lods.empty() ? std::string()
                                            : ", " + std::to_string(character.file_lods.size()) + " MSFT_lod levels")
            << (error ? std::string() : ", " + std::to_string(bytes) + " bytes") << "\n";
  return crowdprof::kExitOk;
}

}  // namespace

void add_gen_command(CLI::App& app, std::function<int()>& run) {
  auto args = std::make_shared<GenArgs>();
  auto* cmd = app.add_subcommand("gen",
                                 "Write the procedural humanoid (69 bones, 4,951 vertices, dance/walk/wave "
                                 "by default) as .glb or .gltf");
  cmd->footer(
      "Examples:\n  crowdprof gen -o big.glb --bones 300 --vertices 20000\n  crowdprof gen -o locomotion.glb --actions "
      "locomotion");
  cmd->add_option("-o,--output", args->output, "File to write; .gltf gives JSON glTF, anything else .glb")
      ->required()
      ->group("Output");
  cmd->add_option("--bones", args->humanoid.bones, "Joint count, 20 to 1024")->capture_default_str();
  cmd->add_option("--vertices", args->humanoid.vertices,
                  "Vertex count, 500 to 2,500,000 (the most the loader takes back)")
      ->capture_default_str();
  cmd->add_option("--seed", args->humanoid.seed, "Varies proportions and motion slightly")->capture_default_str();
  cmd->add_option("--lods", args->humanoid.lod_levels,
                  "Also write this many coarser tessellations of the body (1/2, 1/4, 1/10 of the vertices, at least "
                  "500) as the file's own levels of detail (MSFT_lod), 0 to 3; --mesh-lod on draws them instead of "
                  "simplifying")
      ->capture_default_str();
  cmd->add_option("--actions", args->actions,
                  "default: dance, walk, wave (scenes/humanoid.glb); locomotion: idle, walk, run, for --transitions")
      ->check(CLI::IsMember({"default", "locomotion"}).description(""))
      ->type_name("default|locomotion")
      ->capture_default_str();
  cmd->add_flag("--draco", args->draco, "Compress the mesh with Draco (KHR_draco_mesh_compression)");
  cmd->add_flag(
      "--gltf", args->gltf,
      "Write JSON glTF (buffer embedded as a data: URI) whatever the extension but .glb (refused); an -o ending "
      "in .gltf is JSON glTF without it");
  group_options(*cmd, "Humanoid", {"--bones", "--vertices", "--seed", "--lods", "--actions"});
  group_options(*cmd, "Output", {"--draco", "--gltf"});
  cmd->callback([&run, args] { run = [args] { return gen(*args); }; });
}

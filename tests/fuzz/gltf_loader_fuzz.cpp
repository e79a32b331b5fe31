// Fuzz target: bytes as a .gltf/.glb file (loaded from memory), through everything a frame does with
// a loaded character. The loader must either refuse the file with an InputError
// or hand back characters every job accepts: any other exception, a job whose
// Validate() rejects the loader's output, or a sanitizer report is a finding.
// Draco is reached through KHR_draco_mesh_compression in the seeds.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

#include "animation/binding.h"
#include "animation/local_pose.h"
#include "animation/pose.h"
#include "animation/sampling.h"
#include "asset/asset_report.h"
#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "fuzz_file.h"
#include "skinning/skinning.h"

namespace {

using namespace crowdprof;

void require(bool ok, const char* job) {
  if (ok) return;
  std::fprintf(stderr, "fuzz: the loader's character fails %s::Validate()\n", job);
  std::abort();
}

// One pose of `character` skinned, as a frame of the bench does it.
void pose_and_skin(const Character& character, const SkinningPlan& plan, LocalPose& pose, std::vector<glm::mat4>& model,
                   std::vector<SkinMatrix>& palette, std::vector<glm::vec3>& positions,
                   std::vector<glm::vec3>& normals) {
  require(LocalToModelJob{&character.skeleton, &pose, model}.Run(), "LocalToModelJob");
  require(SkinningMatricesJob{&character.skeleton, model, palette}.Run(), "SkinningMatricesJob");
  require(SkinningJob{palette, &plan, 0, character.mesh.vertex_count(), positions, normals}.Run(), "SkinningJob");
}

void exercise(const Character& character) {
  const size_t joints = character.skeleton.joint_count();
  const size_t vertices = character.mesh.vertex_count();
  LocalPose pose;
  reset_to_rest(character.skeleton, &pose);
  std::vector<glm::mat4> model(joints);
  std::vector<SkinMatrix> palette(joints);
  std::vector<glm::vec3> positions(vertices), normals(vertices);
  // Once per character, as the bench builds it (it was a sixth of the time per
  // input when built for every pose).
  SkinningPlan plan;
  require(build_skinning_plan(character.mesh, character.skeleton.joint_count(), &plan).empty(), "SkinningPlan");
  pose_and_skin(character, plan, pose, model, palette, positions, normals);
  // A few actions at a few times, one of them backwards (the cursor's search).
  for (size_t a = 0; a < std::min<size_t>(character.actions.size(), 3); ++a) {
    const Action& action = character.actions[a];
    ActionBindings bindings = bind_action(character.skeleton, action);
    SamplingCursor cursor;
    reset_cursor(action, &cursor);
    const float mid = action.start + 0.5f * action.duration();
    for (float time : {action.start, mid, action.end, mid, action.end + 1.0f}) {
      reset_to_rest(character.skeleton, &pose);
      require(SamplingJob{&action, time, bindings.targets, &cursor, &pose}.Run(), "SamplingJob");
      pose_and_skin(character, plan, pose, model, palette, positions, normals);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // From memory, as a file of this name in an empty private folder would load:
  // no file written and read back per input.
  static const std::string path = crowdprof::fuzz::input_path("input.gltf");
  try {
    GltfAsset asset = load_gltf_from_memory(std::vector<unsigned char>(data, data + size), path);
    (void)format_asset(asset);  // what `info` prints, over every field
    for (size_t c = 0; c < std::min<size_t>(asset.characters.size(), 4); ++c) exercise(asset.characters[c]);
  } catch (const InputError&) {
    // Refused cleanly: what a bad file should get.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: not an InputError: %s\n", e.what());
    std::abort();
  }
  return 0;
}

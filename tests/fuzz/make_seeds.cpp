// Writes the glTF fuzz target's seed corpus into the first folder given: the
// tests' hand-built skinned character (GLB, .gltf with a data: URI, Draco) and
// the procedural humanoid at its smallest (plain and Draco); and the scene
// target's into the second: scenes of that character ("character.glb" beside
// them in the fuzz target) using every key. Made at build time from the
// project's own code, so no corpus is ever downloaded.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "../draco_fixture.h"
#include "../gltf_fixture.h"
#include "gen/gltf_writer.h"
#include "gen/humanoid.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_seeds GLTF_FOLDER SCENE_FOLDER\n");
    return 2;
  }
  namespace fs = std::filesystem;
  using namespace crowdprof;
  try {
    const fs::path out = argv[1];
    fs::create_directories(out);
    test::SkinnedFixture fixture;
    fixture.write_glb(out / "fixture.glb");
    fixture.write_gltf(out / "fixture_data_uri.gltf", /*data_uri=*/true);
    test::DracoFixture draco;
    draco.write_glb(out / "fixture_draco.glb");
    HumanoidOptions small;
    small.bones = kHumanoidMinBones;
    small.vertices = kHumanoidMinVertices;
    Character humanoid = generate_humanoid(small);
    // One action of a few keys: a seed's cost per execution grows with its JSON
    // and its keys (docs/fuzzing-and-sanitizers.md), while the code that reads
    // them is the same for one.
    humanoid.actions.resize(1);
    Action& action = humanoid.actions[0];
    action.end = action.start;
    for (Channel& channel : action.channels) {
      const size_t keys = std::min<size_t>(channel.key_count(), 6);
      channel.values.resize(channel.values.size() / channel.key_count() * keys);
      channel.times.resize(keys);
      action.end = std::max(action.end, channel.times.back());
    }
    write_gltf(humanoid, (out / "humanoid.glb").string());
    GltfWriteOptions compressed;
    compressed.draco = true;
    write_gltf(humanoid, (out / "humanoid_draco.glb").string(), compressed);

    const fs::path scenes = argv[2];
    fs::create_directories(scenes);
    test::write_file(
        scenes / "shared.json",
        R"({"characters": [{"file": "character.glb", "count": 3, "actions": "shared", "action": "bend"}]})");
    test::write_file(scenes / "everything.json", R"({
  "characters": [
    {"file": "character.glb", "count": 4, "actions": "random", "transitions": 2, "blend_in": 0.5,
     "layers": ["action=bend,mask=joint_1,falloff=1", "action=bend,weight=0.5,blend=add"]},
    {"file": "character.glb#skin=0", "count": 2, "actions": {"bend": 3}, "transitions": 0}
  ],
  "seed": 7,
  "layout": {"type": "grid", "spacing": "auto", "rows": 2, "jitter": 0.3, "seed": 2},
  "camera": {"view": "default", "lens_mm": 35, "sensor_width_mm": 32, "sensor_height_mm": 18, "sensor_fit": "vertical"},
  "resolution": "640x360",
  "mode": "culled",
  "switches": {"share": "on", "share_quantum": "1/30", "update_lod": true, "anim_budget": 2.5, "lod_thresholds": "0.5,0.25,0.125"},
  "threads": 2
})");
    test::write_file(scenes / "placed.json", R"({
  "characters": [{"file": "character.glb", "count": 2}],
  "camera": {"eye": [0.5, 2, 12], "target": [0, 1, 0]},
  "mode": "budget",
  "switches": {"vertex_format": "packed", "transitions": 2, "crossfade": "frozen"}
})");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}

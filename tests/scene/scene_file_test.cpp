// Scene files from the outside: the thesis scene is the default bench, a mixed
// scene runs, the command line overrides what a scene sets, results name the
// scene and its hash, and every malformed scene is one line naming the file
// and the key, exit 3.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scene/scene_file.h"
#include "test_support.h"

using crowdprof::test::read_file;
using crowdprof::test::read_json;
using crowdprof::test::run_cli;
using nlohmann::json;

namespace {

std::string scenes(const std::string& name) {
  return (crowdprof::test::source_dir() / "scenes" / name).string();
}
// The build's copy of the scenes, the folder cmake --install ships.
std::string built_scenes(const std::string& name) {
  return (std::filesystem::path(CROWDPROF_BUILT_SCENES_DIR) / name).string();
}

}  // namespace

TEST(SceneFile, TheThesisSceneIsTheDefaultBench) {
  auto dir = crowdprof::test::scratch_dir("scene_thesis");
  auto a = dir / "scene.json", b = dir / "glb.json";
  auto from_scene =
      run_cli("bench '" + scenes("thesis.json") + "' --frames 2 --warmup 0 -q --json '" + a.string() + "'");
  ASSERT_EQ(from_scene.status, 0) << from_scene.err;
  auto from_glb =
      run_cli("bench '" + scenes("humanoid.glb") + "' -n 160 --frames 2 --warmup 0 -q --json '" + b.string() + "'");
  ASSERT_EQ(from_glb.status, 0) << from_glb.err;
  json scene = read_json(a), glb = read_json(b);
  EXPECT_EQ(scene["digest"], glb["digest"]);
  EXPECT_EQ(scene["counters"], glb["counters"]);
  EXPECT_EQ(scene["scene"]["characters"], 160);
  EXPECT_EQ(scene["scene"]["camera"], "default");
  EXPECT_EQ(scene["scene"]["resolution"], "1600x900");
  // The result names the scene file and a hash of its bytes.
  EXPECT_EQ(scene["scene"]["scene_file"], scenes("thesis.json"));
  EXPECT_EQ(scene["scene"]["scene_hash"], crowdprof::fnv1a64_hex(read_file(scenes("thesis.json"))));
  EXPECT_FALSE(glb["scene"].contains("scene_file"));
  ASSERT_EQ(scene["crowd"].size(), 1u);
  EXPECT_EQ(scene["crowd"][0]["file"], "humanoid.glb");
  // Blender's default camera: 36 of the 160 copies fall outside it (42 with the
  // old 49.1 degrees vertical, a much wider shot).
  EXPECT_EQ(scene["counters"]["copies_culled"], 36);
}

TEST(SceneFile, AMixedSceneShowsEachCharacter) {
  auto dir = crowdprof::test::scratch_dir("scene_mixed");
  auto out = dir / "mixed.json";
  auto r = run_cli("bench '" + scenes("mixed.json") + "' --frames 2 --warmup 1 --json '" + out.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  json j = read_json(out);
  ASSERT_EQ(j["crowd"].size(), 3u);
  uint64_t copies = 0, poses = 0, culled = 0, skinned = 0, visible = 0;
  for (const json& c : j["crowd"]) {
    copies += c["copies"].get<uint64_t>();
    poses += c["counters"]["poses_updated"].get<uint64_t>();
    culled += c["counters"]["copies_culled"].get<uint64_t>();
    visible += c["counters"]["copies_visible"].get<uint64_t>();
    skinned += c["counters"]["vertices_skinned"].get<uint64_t>();
    EXPECT_EQ(c["counters"]["vertices_skinned"].get<uint64_t>(),
              c["counters"]["poses_updated"].get<uint64_t>() * c["vertices"].get<uint64_t>());
  }
  EXPECT_EQ(copies, 160u);
  EXPECT_EQ(j["crowd"][0]["copies"], 80);
  EXPECT_EQ(j["crowd"][1]["joints"], 300);
  EXPECT_EQ(j["crowd"][1]["action_choice"], "weighted");
  EXPECT_EQ(poses, j["counters"]["poses_updated"].get<uint64_t>());
  EXPECT_EQ(culled, j["counters"]["copies_culled"].get<uint64_t>());
  EXPECT_EQ(visible, j["counters"]["copies_visible"].get<uint64_t>());
  EXPECT_EQ(skinned, j["counters"]["vertices_skinned"].get<uint64_t>());
  EXPECT_EQ(j["scene"]["action_choice"], "scene");
  // The table shows a row per character.
  EXPECT_NE(r.out.find("gen --bones 300 --vertices 12000 --seed 3 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("160 characters of 3 kinds"), std::string::npos) << r.out;
  // The same scene gives the same bits again.
  auto again = dir / "again.json";
  ASSERT_EQ(run_cli("bench '" + built_scenes("mixed.json") + "' --frames 2 --warmup 1 -q --threads 1 --json '" +
                    again.string() + "'")
                .status,
            0);
  EXPECT_EQ(read_json(again)["digest"], j["digest"]);
}

TEST(SceneFile, TheCommandLineOverridesTheScene) {
  auto dir = crowdprof::test::scratch_dir("scene_override");
  auto out = dir / "r.json";
  auto r = run_cli("bench '" + built_scenes("mixed.json") +
                   "' -n 16 --camera all --seed 5 --lens 50 --resolution 640x480 "
                   "--actions random --frames 1 --warmup 0 -q --json '" +
                   out.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  json j = read_json(out);
  EXPECT_EQ(j["scene"]["characters"], 16);
  EXPECT_EQ(j["scene"]["camera"], "all");
  EXPECT_EQ(j["scene"]["seed"], 5);
  EXPECT_EQ(j["scene"]["resolution"], "640x480");
  EXPECT_EQ(j["scene"]["lens"]["focal_mm"], 50.0);
  EXPECT_EQ(j["scene"]["action_choice"], "random");
  EXPECT_EQ(j["crowd"][0]["copies"], 8);  // 80:40:40 scaled to 16
  EXPECT_EQ(j["crowd"][1]["copies"], 4);
  EXPECT_EQ(j["crowd"][2]["action_choice"], "random");
  EXPECT_EQ(j["counters"]["copies_culled"], 0);  // camera all
}

TEST(SceneFile, CheckRerunsASceneBaselineWithItsOverrides) {
  auto dir = crowdprof::test::scratch_dir("scene_check");
  auto base = dir / "base.json";
  ASSERT_EQ(run_cli("bench '" + built_scenes("mixed.json") + "' -n 12 --seed 9 --frames 6 --warmup 0 -q --json '" +
                    base.string() + "'")
                .status,
            0);
  auto r = run_cli("check --spread 0 --baseline '" + base.string() + "' --tolerance 1000%");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("counters and digest match"), std::string::npos) << r.out;  // the same work
}

TEST(SceneFile, HardwareSkinningFallsBackPerCharacter) {
  if (!crowdprof::test::have_gl()) GTEST_SKIP() << "no GL backend on this machine";
  auto dir = crowdprof::test::scratch_dir("scene_hwskin");
  auto out = dir / "r.json";
  auto r = run_cli("bench '" + built_scenes("mixed.json") +
                   "' -n 12 --mode hwskin --backend auto --resolution 320x180 "
                   "--frames 1 --warmup 0 -q --json '" +
                   out.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  json j = read_json(out);
  // The 300-bone character is over the 128-bone limit: skinned on the CPU.
  EXPECT_EQ(j["crowd"][1]["counters"]["copies_fallback"], j["crowd"][1]["counters"]["poses_updated"]);
  EXPECT_GT(j["crowd"][1]["counters"]["copies_fallback"].get<uint64_t>(), 0u);
  EXPECT_EQ(j["crowd"][0]["counters"]["copies_fallback"], 0);
  EXPECT_EQ(j["crowd"][0]["counters"]["vertices_skinned"], 0);
  EXPECT_EQ(j["crowd"][2]["counters"]["copies_fallback"], 0);
  EXPECT_EQ(j["counters"]["copies_fallback"], j["crowd"][1]["counters"]["copies_fallback"]);
  EXPECT_EQ(j["counters"]["draw_calls"], j["counters"]["copies_visible"]);
}

// Each malformed scene: exit 3 and one line naming the file and the key.
TEST(SceneFile, MalformedScenesNameTheFileAndTheKey) {
  auto dir = crowdprof::test::scratch_dir("scene_bad");
  std::string glb = scenes("humanoid.glb");
  std::string ok_character = "{\"file\": \"" + glb + "\", \"count\": 2}";
  struct Case {
    std::string text, key;
  };
  std::vector<Case> cases = {
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"colour\": \"red\"}]}", "characters[0].colour"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": \"ten\"}]}", "characters[0].count"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": -3}]}", "characters[0].count"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2.5}]}", "characters[0].count"},
      {"{\"characters\": [" + ok_character + ", {\"file\": \"nowhere.glb\", \"count\": 1}]}", "characters[1].file"},
      {"{\"characters\": [{\"count\": 1}]}", "characters[0].file"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"generate\": {}, \"count\": 1}]}", "characters[0].generate"},
      {"{\"characters\": [{\"generate\": {\"bones\": 5}, \"count\": 1}]}", "characters[0].generate.bones"},
      {"{\"characters\": [{\"generate\": {\"vertices\": 1e9}, \"count\": 1}]}", "characters[0].generate.vertices"},
      {"{\"characters\": [{\"generate\": {\"draco\": \"yes\"}, \"count\": 1}]}", "characters[0].generate.draco"},
      {"{\"characters\": [{\"generate\": {\"lods\": 4}, \"count\": 1}]}", "characters[0].generate.lods"},
      {"{\"characters\": [{\"generate\": {\"size\": 2}, \"count\": 1}]}", "characters[0].generate.size"},
      {"{\"characters\": [{\"generate\": {\"actions\": \"dance\"}, \"count\": 1}]}", "characters[0].generate.actions"},
      {"{\"characters\": [{\"generate\": [], \"count\": 1}]}", "characters[0].generate"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 0}]}", "characters"},
      {"{\"characters\": []}", "characters"},
      {"{}", "characters"},
      {"{\"characters\": [" + ok_character + "], \"cameras\": {}}", "cameras"},
      {"{\"characters\": [" + ok_character + "], \"seed\": -1}", "seed"},
      {"{\"characters\": [" + ok_character + "], \"layout\": {\"rows\": \"many\"}}", "layout.rows"},
      {"{\"characters\": [" + ok_character + "], \"layout\": {\"type\": \"circle\"}}", "layout.type"},
      {"{\"characters\": [" + ok_character + "], \"layout\": {\"jitter\": -1}}", "layout.jitter"},
      {"{\"characters\": [" + ok_character + "], \"camera\": {\"view\": \"sideways\"}}", "camera.view"},
      {"{\"characters\": [" + ok_character + "], \"camera\": {\"eye\": [0, 1], \"target\": [0, 0, 0]}}", "camera.eye"},
      {"{\"characters\": [" + ok_character + "], \"camera\": {\"eye\": [0, 1, 2]}}", "camera.target"},
      {"{\"characters\": [" + ok_character + "], \"camera\": {\"lens_mm\": 0}}", "camera.lens_mm"},
      {"{\"characters\": [" + ok_character + "], \"camera\": {\"sensor_fit\": \"diagonal\"}}", "camera.sensor_fit"},
      {"{\"characters\": [" + ok_character + "], \"resolution\": \"big\"}", "resolution"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"actions\": \"some\"}]}", "characters[0].actions"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"action\": \"fly\"}]}", "characters[0].action"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"actions\": {\"fly\": 1}}]}",
       "characters[0].actions.fly"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"actions\": {\"walk\": 0}}]}",
       "characters[0].actions"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"actions\": {\"walk\": \"x\"}}]}",
       "characters[0].actions.walk"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"transitions\": 0.01}]}",
       "characters[0].transitions"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"transitions\": \"often\"}]}",
       "characters[0].transitions"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"blend_in\": 0.5}]}", "characters[0].blend_in"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"transitions\": 2, \"blend_in\": 1.5}]}",
       "characters[0].blend_in"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"transitions\": 0.3}]}",
       "characters[0].blend_in: the default 0.25 s"},
      {"{\"characters\": [" + ok_character + "]", "truncated JSON"},
      {"{\"characters\": [" + ok_character + "], \"seed\": 1e400}", "a number too large for a double"},
      {"{\"characters\": [" + ok_character + "]]}", "broken JSON"},
      {"{\"characters\": [{\"file\": \"" + glb + "\", \"count\": 2, \"count\": 3}]}",
       "the key \"count\" is given twice in one object"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    auto path = dir / ("bad" + std::to_string(i) + ".json");
    std::ofstream(path) << cases[i].text;
    auto r = run_cli("bench '" + path.string() + "' --frames 1 --warmup 0 -q");
    EXPECT_EQ(r.status, 3) << cases[i].text << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(path.string() + ": " + cases[i].key), std::string::npos) << cases[i].text << "\n" << r.err;
  }
}

// Each group changes action on its own timing: its "transitions" over the
// command line's, 0 keeping its action while others change.
TEST(SceneFile, EachGroupFadesOnItsOwnTiming) {
  auto dir = crowdprof::test::scratch_dir("scene_transitions");
  const std::string glb = scenes("humanoid.glb");
  auto scene = dir / "fading.json";
  std::ofstream(scene) << "{\"characters\": [{\"file\": \"" << glb
                       << "\", \"count\": 30, \"actions\": \"random\", \"transitions\": 0.5, \"blend_in\": 0.2},"
                          " {\"file\": \""
                       << glb << "\", \"count\": 30, \"actions\": \"random\", \"transitions\": 0}]}";
  auto alone = dir / "alone.json", over = dir / "over.json", plain = dir / "plain.json";
  // No --transitions: the first group's own still fade.
  auto r =
      run_cli("bench '" + scene.string() + "' --camera all --frames 60 --warmup 0 -q --json '" + alone.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  json a = read_json(alone);
  EXPECT_GT(a["counters"]["fades"].get<int>(), 0);
  // About 0.2 / 0.5 of the first group's 30 copies fade in a frame, none of
  // the second's: about half as many as when both groups change.
  auto both = dir / "both.json", both_result = dir / "both_result.json";
  std::ofstream(both) << "{\"characters\": [{\"file\": \"" << glb
                      << "\", \"count\": 30, \"actions\": \"random\", \"transitions\": 0.5, \"blend_in\": 0.2},"
                         " {\"file\": \""
                      << glb
                      << "\", \"count\": 30, \"actions\": \"random\", \"transitions\": 0.5, "
                         "\"blend_in\": 0.2}]}";
  r = run_cli("bench '" + both.string() + "' --camera all --frames 60 --warmup 0 -q --json '" + both_result.string() +
              "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const int fades_alone = a["counters"]["fades"].get<int>(), fades_both = read_json(both_result)["counters"]["fades"];
  EXPECT_LE(fades_alone, 20);
  EXPECT_GT(fades_both, fades_alone * 3 / 2) << fades_alone << " fades with one group changing";
  // The command line's timing reaches neither group: both state their own.
  r = run_cli("bench '" + scene.string() + "' --camera all --frames 60 --warmup 0 -q --transitions 100 --json '" +
              over.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_json(over)["digest"], a["digest"]);
  // Without the groups' timings, a scene of the same crowd loops its actions.
  auto looping = dir / "looping.json";
  std::ofstream(looping) << "{\"characters\": [{\"file\": \"" << glb
                         << "\", \"count\": 30, \"actions\": \"random\"},"
                            " {\"file\": \""
                         << glb << "\", \"count\": 30, \"actions\": \"random\"}]}";
  r = run_cli("bench '" + looping.string() + "' --camera all --frames 60 --warmup 0 -q --json '" + plain.string() +
              "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_json(plain)["counters"]["fades"], 0);
  EXPECT_NE(read_json(plain)["digest"], a["digest"]);
}

TEST(SceneFile, CheckSaysWhenTheSceneFileChanged) {
  auto dir = crowdprof::test::scratch_dir("scene_edited");
  auto scene = dir / "s.json", base = dir / "base.json";
  std::string glb = scenes("humanoid.glb");
  std::ofstream(scene) << "{\"characters\": [{\"file\": \"" << glb << "\", \"count\": 6}]}";
  ASSERT_EQ(run_cli("bench '" + scene.string() + "' --frames 4 --warmup 0 -q --json '" + base.string() + "'").status,
            0);
  std::ofstream(scene) << "{\"characters\": [{\"file\": \"" << glb << "\", \"count\": 6, \"action\": \"walk\"}]}";
  auto r = run_cli("check --spread 0 --baseline '" + base.string() + "' --tolerance 1000%");
  EXPECT_EQ(r.status, 1) << r.out << r.err;  // they play another action: another digest
  EXPECT_NE(r.err.find("the scene file changed since the baseline"), std::string::npos) << r.err;
}

TEST(SceneFile, InfoDescribesEachCharacterOfAScene) {
  auto r = run_cli("info '" + built_scenes("mixed.json") + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("characters[1]: gen --bones 300 --vertices 12000 --seed 3, 40 copies"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("joints:      300"), std::string::npos) << r.out;
  auto j = run_cli("info '" + built_scenes("mixed.json") + "' --json");
  ASSERT_EQ(j.status, 0) << j.err;
  json doc = json::parse(j.out);
  ASSERT_EQ(doc["characters"].size(), 3u);
  EXPECT_EQ(doc["characters"][2]["count"], 40);
  EXPECT_EQ(doc["scene_hash"], crowdprof::fnv1a64_hex(read_file(built_scenes("mixed.json"))));
  auto dir = crowdprof::test::scratch_dir("scene_info_bad");
  auto bad = dir / "bad.json";
  std::ofstream(bad) << "{\"characters\": [{\"file\": \"missing.glb\", \"count\": 1}]}";
  auto refused = run_cli("info '" + bad.string() + "'");
  EXPECT_EQ(refused.status, 3);
  EXPECT_NE(refused.err.find("characters[0].file"), std::string::npos) << refused.err;
}

// A "generate" entry is the humanoid `crowdprof gen` writes with the same
// options, loaded from its bytes as that file would be: the same crowd, digest
// and asset hash; results name it by the gen command; the scene runs from any
// folder, with no file beside it.
TEST(SceneFile, AGeneratedCharacterIsTheFileGenWouldWrite) {
  auto dir = crowdprof::test::scratch_dir("scene_generate");
  const std::string glb = (dir / "h.glb").string();
  ASSERT_EQ(run_cli("gen -o '" + glb + "' --bones 30 --vertices 800 --seed 4 --actions locomotion --draco").status, 0);
  auto from_file = dir / "file.json", generated = dir / "generated.json";
  std::ofstream(from_file) << "{\"characters\": [{\"file\": \"h.glb\", \"count\": 6, \"actions\": \"random\"}]}";
  std::ofstream(generated) << "{\"characters\": [{\"generate\": {\"bones\": 30, \"vertices\": 800, \"seed\": 4, "
                              "\"actions\": \"locomotion\", \"draco\": true}, \"count\": 6, \"actions\": \"random\"}]}";
  auto a = dir / "a.json", b = dir / "b.json";
  auto r = run_cli("bench '" + from_file.string() + "' --frames 2 --warmup 0 -q --json '" + a.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_cli("bench '" + generated.string() + "' --frames 2 --warmup 0 -q --json '" + b.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const json ja = read_json(a), jb = read_json(b);
  EXPECT_EQ(ja["digest"], jb["digest"]);
  EXPECT_EQ(ja["counters"], jb["counters"]);
  EXPECT_EQ(ja["crowd"][0]["asset_hash"], jb["crowd"][0]["asset_hash"]);
  EXPECT_EQ(jb["crowd"][0]["file"], "gen --bones 30 --vertices 800 --seed 4 --actions locomotion --draco");
  // info describes it as it describes the file.
  auto info = run_cli("info '" + generated.string() + "'");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_NE(
      info.out.find("characters[0]: gen --bones 30 --vertices 800 --seed 4 --actions locomotion --draco, 6 copies"),
      std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("joints:      30 "), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("(Draco decoded)"), std::string::npos) << info.out;
}

TEST(SceneFile, EachGroupLaysItsOwnLayers) {
  auto dir = crowdprof::test::scratch_dir("scene_layers");
  auto scene = dir / "layered.json";
  // The locomotion character: idle over the walk on the first group's upper
  // body; the second group plays its own action alone.
  std::ofstream(scene) << R"({"characters": [
    {"generate": {"actions": "locomotion"}, "count": 30, "actions": "shared", "action": "walk",
     "layers": ["action=idle,mask=spine_03,falloff=2"]},
    {"generate": {"actions": "locomotion", "seed": 2}, "count": 10, "actions": "shared", "action": "walk"}]})";
  auto own = dir / "own.json", over = dir / "over.json", none = dir / "none.json", again = dir / "again.json";
  auto out = dir / "out.json";
  const std::string run = "bench '" + scene.string() + "' --camera all --frames 4 --warmup 0 -q ";
  auto r = run_cli(run + "--json '" + own.string() + "' --scene-out '" + out.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  json a = read_json(own);
  // One layer per posed copy of the first group: 30 with every copy on screen.
  EXPECT_EQ(a["counters"]["layers"], 30);
  // --anim-layer reaches the group that states none; the first keeps its own.
  r = run_cli(run + "--anim-layer action=run,mask=spine_03 --json '" + over.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_json(over)["counters"]["layers"], 40);
  EXPECT_NE(read_json(over)["digest"], a["digest"]);
  // Without the group's layers the crowd is another.
  std::string text = read_file(scene);
  text.replace(text.find("\"layers\""), std::string("\"layers\": [\"action=idle,mask=spine_03,falloff=2\"]").size(),
               "\"layers\": []");
  std::ofstream(dir / "plain.json") << text;
  r = run_cli("bench '" + (dir / "plain.json").string() + "' --camera all --frames 4 --warmup 0 -q --json '" +
              none.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_json(none)["counters"]["layers"], 0);
  EXPECT_NE(read_json(none)["digest"], a["digest"]);
  // --scene-out keeps the group's layers: the same frames again.
  EXPECT_NE(read_file(out).find("\"action=idle,mask=spine_03,weight=1,falloff=2,blend=override\""), std::string::npos);
  r = run_cli("bench '" + out.string() + "' --camera all --frames 4 --warmup 0 -q --json '" + again.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_json(again)["digest"], a["digest"]);
  // A layer the character cannot play names the file and the key, exit 3.
  for (const auto& [layer, why] : {std::pair{std::string("action=fly"), std::string("no action 'fly'")},
                                   {std::string("action=idle,mask=tail"), std::string("no joint 'tail'")},
                                   {std::string("action=idle,weight=2"), std::string("weight")}}) {
    auto bad = dir / "bad.json";
    std::ofstream(bad) << R"({"characters": [{"generate": {"actions": "locomotion"}, "count": 2, "layers": [")" << layer
                       << R"("]}]})";
    r = run_cli("bench '" + bad.string() + "' --frames 1 --warmup 0 -q");
    EXPECT_EQ(r.status, 3) << layer << "\n" << r.err;
    EXPECT_NE(r.err.find(bad.string() + ": characters[0].layers"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
  }
  // So does the scene's own anim_layer switch: the file's fault, not --anim-layer's.
  auto bad = dir / "bad_switch.json";
  std::ofstream(bad) << R"({"characters": [{"generate": {"actions": "locomotion"}, "count": 2}],
    "switches": {"anim_layer": "action=fly"}})";
  r = run_cli("bench '" + bad.string() + "' --frames 1 --warmup 0 -q");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find(bad.string() + ": switches.anim_layer: no action 'fly'"), std::string::npos) << r.err;
  // A switch given over the scene's replaces it: the scene's is not played, nor judged.
  r = run_cli("bench '" + bad.string() + "' --frames 1 --warmup 0 -q --anim-layer action=idle");
  EXPECT_EQ(r.status, 0) << r.err;
}

// Scene files that say how they run ("mode", "switches", "threads"): they run
// as the same options on the command line do, the command line wins, compare
// applies their switches to every mode, check re-runs their baselines exactly,
// bad values are one line naming the key; and bench --scene-out writes a run's
// configuration as a scene that bench runs as is.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "scene/scene_file.h"
#include "test_support.h"

using crowdprof::test::read_file;
using crowdprof::test::read_json;
using crowdprof::test::run_cli;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string shipped(const std::string& name) {
  return (crowdprof::test::source_dir() / "scenes" / name).string();
}
std::string built(const std::string& name) {
  return (fs::path(CROWDPROF_BUILT_SCENES_DIR) / name).string();
}

// A scene of `count` humanoids with `extra` keys after its characters.
std::string humanoid_scene(int count, const std::string& extra) {
  return "{\"characters\": [{\"file\": \"" + shipped("humanoid.glb") + "\", \"count\": " + std::to_string(count) +
         "}]" + (extra.empty() ? "" : ", " + extra) + "}";
}

// Runs `bench ARGS --json OUT` for a few frames; the result.
json bench_json(const std::string& args, const fs::path& out) {
  auto r = run_cli("bench " + args + " --frames 3 --warmup 0 -q --json '" + out.string() + "'");
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  return r.status == 0 ? read_json(out) : json();
}

}  // namespace

TEST(SceneMode, ModeAndSwitchesRunAsTheirOptionsDo) {
  auto dir = crowdprof::test::scratch_dir("scene_mode_as_options");
  auto scene = dir / "s.json";
  // Values as users type them and as results record them (true, a number).
  std::ofstream(scene) << humanoid_scene(
      12,
      "\"mode\": \"culled\", \"switches\": {\"share\": \"on\", \"share_quantum\": \"1/30\", \"update_lod\": true, "
      "\"lod_thresholds\": \"0.5,0.25,0.125\", \"anim_budget\": 0}");
  json a = bench_json("'" + scene.string() + "'", dir / "a.json");
  json b = bench_json("'" + shipped("humanoid.glb") +
                          "' -n 12 --mode culled --share on --share-quantum 1/30 --update-lod on "
                          "--lod-thresholds 0.5,0.25,0.125",
                      dir / "b.json");
  ASSERT_FALSE(a.is_null() || b.is_null());
  EXPECT_EQ(a["mode"], "culled+custom");
  EXPECT_EQ(a["mode"], b["mode"]);
  EXPECT_EQ(a["switches"], b["switches"]);
  EXPECT_EQ(a["switches"]["share"], true);
  EXPECT_EQ(a["switches"]["update_lod"], true);
  EXPECT_EQ(a["digest"], b["digest"]);
  EXPECT_EQ(a["counters"], b["counters"]);
}

TEST(SceneMode, TheCommandLineWins) {
  auto dir = crowdprof::test::scratch_dir("scene_mode_command_line");
  auto scene = dir / "s.json";
  std::ofstream(scene) << humanoid_scene(
      10, "\"mode\": \"master\", \"switches\": {\"share\": \"on\", \"share_quantum\": 0.05}, \"threads\": 3");
  // Alone: the scene's mode and switches (master runs on one thread: its threads do not apply).
  json alone = bench_json("'" + scene.string() + "'", dir / "alone.json");
  EXPECT_EQ(alone["mode"], "master+custom");
  EXPECT_EQ(alone["switches"]["share"], true);
  EXPECT_EQ(alone["switches"]["share_quantum"], 0.05);
  // --mode replaces the scene's mode, not its switches; a switch option replaces the scene's.
  json over = bench_json("'" + scene.string() + "' --mode threaded --share-quantum 0", dir / "over.json");
  json same =
      bench_json("'" + shipped("humanoid.glb") + "' -n 10 --mode threaded --share on --threads 3", dir / "same.json");
  EXPECT_EQ(over["mode"], "threaded+custom");
  EXPECT_EQ(over["switches"]["share"], true);
  EXPECT_EQ(over["switches"].value("share_quantum", 0.0), 0.0);  // at its plain value: left out
  EXPECT_EQ(over["switches"], same["switches"]);
  EXPECT_EQ(over["digest"], same["digest"]);
  EXPECT_EQ(over["counters"], same["counters"]);
  // The scene's threads apply to a parallel mode; the command line's win.
  EXPECT_EQ(over["threads"], same["threads"]);
  json two = bench_json("'" + scene.string() + "' --mode threaded --threads 2", dir / "two.json");
  EXPECT_NE(two["threads"], over["threads"]);
}

TEST(SceneMode, CompareAppliesTheSceneSwitchesToEveryMode) {
  auto dir = crowdprof::test::scratch_dir("scene_mode_compare");
  auto scene = dir / "s.json", out = dir / "c.json";
  std::ofstream(scene) << humanoid_scene(8, "\"mode\": \"master\", \"switches\": {\"vertex_format\": \"packed\"}");
  auto r = run_cli("compare '" + scene.string() +
                   "' --modes culled,threaded,threaded+vertex-format=float --frames 2 --warmup 0 --block 1 -q "
                   "--backend none --json '" +
                   out.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  json j = read_json(out);
  ASSERT_EQ(j["runs"].size(), 3u) << j.dump();
  EXPECT_EQ(j["runs"][0]["mode"], "culled+custom");  // --modes wins over the scene's master
  EXPECT_EQ(j["runs"][0]["switches"]["vertex_format"], "packed");
  EXPECT_EQ(j["runs"][1]["mode"], "threaded+custom");
  EXPECT_EQ(j["runs"][1]["switches"]["vertex_format"], "packed");
  EXPECT_EQ(j["runs"][2]["switches"].value("vertex_format", "float"), "float");  // the list's own wins
}

TEST(SceneMode, CheckRerunsTheConfigurationTheBaselineRan) {
  auto dir = crowdprof::test::scratch_dir("scene_mode_check");
  auto scene = dir / "s.json", base = dir / "base.json", run = dir / "run.json";
  // Mode shared with share off: a switch at its plain value, which a result
  // leaves out, yet not the preset's.
  std::ofstream(scene) << humanoid_scene(
      10, "\"mode\": \"shared\", \"switches\": {\"share\": \"off\", \"update_lod\": \"on\"}, \"threads\": 2");
  auto made = run_cli("check --spread 0 '" + scene.string() + "' --frames 4 --warmup 0 --runs 1 --baseline '" +
                      base.string() + "' --update-baseline -q");
  ASSERT_EQ(made.status, 0) << made.err;
  json b = read_json(base);
  EXPECT_EQ(b["mode"], "shared+custom");
  EXPECT_EQ(b["switches"].value("share", false), false);
  EXPECT_EQ(b["switches"]["update_lod"], true);
  auto again = run_cli("check --spread 0 '" + scene.string() + "' --baseline '" + base.string() +
                       "' --tolerance 1000% --json '" + run.string() + "'");
  EXPECT_EQ(again.status, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("counters and digest match"), std::string::npos) << again.out;
  json r = read_json(run);
  EXPECT_EQ(r["mode"], b["mode"]);
  EXPECT_EQ(r["switches"], b["switches"]);
  // The scene's switches edited since: the baseline's record is what re-runs.
  std::ofstream(scene) << humanoid_scene(10, "\"mode\": \"shared\", \"switches\": {\"update_lod\": \"off\"}");
  auto edited = run_cli("check --spread 0 '" + scene.string() + "' --baseline '" + base.string() +
                        "' --tolerance 1000% --json '" + run.string() + "'");
  EXPECT_EQ(edited.status, 0) << edited.out << edited.err;
  EXPECT_NE(edited.err.find("the scene file changed since the baseline"), std::string::npos) << edited.err;
  EXPECT_EQ(read_json(run)["switches"], b["switches"]);
}

TEST(SceneMode, ABadModeOrSwitchIsOneLineNamingTheKey) {
  auto dir = crowdprof::test::scratch_dir("scene_mode_bad");
  struct Case {
    std::string extra, message;
  };
  std::vector<Case> cases = {
      {"\"mode\": \"fast\"", "mode: 'fast': expected one of master, culled, threaded"},
      {"\"mode\": 3", "mode: expected a string, got a whole number"},
      {"\"switches\": [\"culling\"]", "switches: expected an object of switches by name"},
      {"\"switches\": {\"sharing\": \"on\"}", "switches.sharing: no such switch (the switches are lookups, culling"},
      {"\"switches\": {\"culling\": \"maybe\"}", "switches.culling: 'maybe': expected on or off"},
      {"\"switches\": {\"culling\": null}",
       "switches.culling: expected a value as the option --culling takes (on|off)"},
      {"\"switches\": {\"pose\": true}", "switches.pose: 'on': expected one of"},
      {"\"switches\": {\"share_quantum\": -1}", "switches.share_quantum: '-1': expected seconds from 0 to 10"},
      {"\"switches\": {\"pose\": \"shared\"}", "switches: with mode threaded: a shared scratch pose"},
      {"\"mode\": \"master\", \"switches\": {\"parallel\": \"on\"}", "switches: with mode master: "},
      {"\"threads\": 0", "threads: 0 is out of range (1 to 1024)"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    auto path = dir / ("bad" + std::to_string(i) + ".json");
    std::ofstream(path) << humanoid_scene(2, cases[i].extra);
    for (const char* command : {"bench", "compare"}) {
      auto r = run_cli(std::string(command) + " '" + path.string() + "' --frames 1 --warmup 0 -q");
      EXPECT_EQ(r.status, 3) << cases[i].extra << "\n" << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_NE(r.err.find(path.string() + ": " + cases[i].message), std::string::npos) << r.err;
    }
  }
}

// The codec: what scene_file_text writes, load_scene_file reads back as the
// same scene, from another folder too.
TEST(SceneMode, AWrittenSceneReadsBackTheSame) {
  auto dir = crowdprof::test::scratch_dir("scene_mode_codec");
  fs::create_directories(dir / "elsewhere");
  auto scene = dir / "s.json";
  std::ofstream(scene) << R"({
  "characters": [
    {"file": "../../scenes/humanoid.glb#skin=0", "count": 4, "actions": {"walk": 3, "wave": 1}, "transitions": 2, "blend_in": 0.5},
    {"generate": {"bones": 300, "seed": 3, "draco": true}, "count": 2, "actions": "shared", "action": "wave"},
    {"file": ")" + shipped("humanoid.glb") +
                              R"(", "count": 0, "actions": "random"}
  ],
  "seed": 7,
  "layout": {"spacing": 1.5, "rows": 2, "jitter": 0.3, "seed": 2},
  "camera": {"eye": [0.1, 2, 12], "target": [0, 1, 0], "lens_mm": 50, "sensor_fit": "vertical"},
  "resolution": "640x360",
  "mode": "budget",
  "switches": {"anim_budget": 2.5, "share_quantum": "1/30", "culling": true},
  "threads": 4
})";
  // The first file is relative to the scene's folder: put the scene where that reaches the checkout.
  fs::path nested = crowdprof::test::source_dir() / "build-scene-codec-test" / "a";
  fs::create_directories(nested);
  fs::copy_file(scene, nested / "s.json", fs::copy_options::overwrite_existing);
  const crowdprof::SceneFile a = crowdprof::load_scene_file((nested / "s.json").string());
  const std::string written = (dir / "elsewhere" / "w.json").string();
  std::ofstream(written) << crowdprof::scene_file_text(a, written);
  const crowdprof::SceneFile b = crowdprof::load_scene_file(written);
  fs::remove_all(crowdprof::test::source_dir() / "build-scene-codec-test");
  ASSERT_EQ(b.characters.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const auto &ca = a.characters[k], &cb = b.characters[k];
    EXPECT_EQ(ca.count, cb.count);
    EXPECT_EQ(ca.actions, cb.actions);
    EXPECT_EQ(ca.action, cb.action);
    EXPECT_EQ(ca.weights.size(), cb.weights.size());
    EXPECT_EQ(ca.generate.has_value(), cb.generate.has_value());
    EXPECT_EQ(ca.file.empty(), cb.file.empty());
    if (!ca.generate)  // the same file on disk, named from another folder
      EXPECT_EQ(fs::weakly_canonical(ca.path.substr(0, ca.path.find('#'))),
                fs::weakly_canonical(cb.path.substr(0, cb.path.find('#'))));
    else
      EXPECT_EQ(ca.file, cb.file);  // the gen command: the same options
  }
  EXPECT_NE(b.characters[0].path.find("#skin=0"), std::string::npos);
  EXPECT_EQ(b.characters[0].transitions->mean_s, 2.0);
  EXPECT_EQ(b.characters[0].transitions->blend_in_s, 0.5);
  EXPECT_EQ(b.seed, 7u);
  EXPECT_EQ(b.layout.spacing, 1.5f);
  EXPECT_EQ(b.layout.rows, 2u);
  EXPECT_EQ(b.layout.jitter, 0.3f);
  EXPECT_EQ(b.layout.jitter_seed, 2u);
  EXPECT_EQ(b.camera, a.camera);
  EXPECT_EQ(b.lens.focal_mm, 50.0f);
  EXPECT_EQ(b.lens.fit, crowdprof::SensorFit::Vertical);
  EXPECT_EQ(b.resolution, "640x360");
  EXPECT_EQ(b.mode, "budget");
  EXPECT_EQ(b.switches, a.switches);
  EXPECT_EQ(b.switches.at("culling"), "on");
  EXPECT_EQ(b.switches.at("share_quantum"), "1/30");
  EXPECT_EQ(b.threads, 4);
  // Written again from where it lies: the same text.
  EXPECT_EQ(crowdprof::scene_file_text(b, written), read_file(written));
}

// bench --scene-out: the scene bench runs as is, giving the same crowd,
// counters and digest as the command that wrote it.
TEST(SceneOut, BenchRunsTheSceneItWroteAsIs) {
  auto dir = crowdprof::test::scratch_dir("scene_out_replays");
  fs::create_directories(dir / "sub");
  const std::vector<std::string> commands = {
      // A character file with every scene setting on the command line.
      "'" + shipped("humanoid.glb") +
          "' -n 20 --actions random --seed 4 --camera 0.5,2,12,0,1,0 --lens 50 --resolution 640x360 "
          "--mode threaded --threads 2 --share on --share-quantum 1/30 --update-lod on",
      "'" + shipped("humanoid.glb") + "' -n 6 --action walk --mode culled",
      // Generated characters, weighted actions, counts scaled by -n (budget
      // without its time-driven budget: no test asserts a time).
      "'" + built("mixed.json") + "' -n 30 --mode budget --anim-budget 0 --camera all",
      // Groups with their own transitions, and the run's.
      "'" + built("locomotion.json") + "' -n 25 --transitions 2 --crossfade frozen --mode shared",
      // A scene's mode and switches, one replaced.
      "'" + built("mixed.json") + "' -n 12 --actions shared --action wave",
  };
  for (size_t i = 0; i < commands.size(); ++i) {
    const fs::path out = dir / "sub" / ("scene" + std::to_string(i) + ".json");
    json a = bench_json(commands[i] + " --scene-out '" + out.string() + "'", dir / "a.json");
    ASSERT_FALSE(a.is_null());
    json scene = json::parse(read_file(out));
    EXPECT_TRUE(scene.contains("mode")) << scene.dump();
    json b = bench_json("'" + out.string() + "'", dir / "b.json");
    ASSERT_FALSE(b.is_null()) << scene.dump(2);
    EXPECT_EQ(a["digest"], b["digest"]) << commands[i] << "\n" << scene.dump(2);
    EXPECT_EQ(a["counters"], b["counters"]) << commands[i];
    EXPECT_EQ(a["mode"], b["mode"]) << commands[i];
    EXPECT_EQ(a["switches"], b["switches"]) << commands[i];
    EXPECT_EQ(a["threads"], b["threads"]) << commands[i];
    // (The run's action_choice is "scene" now: each group's is compared below.)
    for (const char* key : {"characters", "seed", "camera", "resolution", "lens"})
      EXPECT_EQ(a["scene"][key], b["scene"][key]) << commands[i] << ": " << key;
    ASSERT_EQ(a["crowd"].size(), b["crowd"].size());
    for (size_t k = 0; k < a["crowd"].size(); ++k) {
      EXPECT_EQ(a["crowd"][k]["copies"], b["crowd"][k]["copies"]) << commands[i];
      EXPECT_EQ(a["crowd"][k]["action_choice"], b["crowd"][k]["action_choice"]) << commands[i];
    }
    // Written again from the scene it wrote: the same file.
    const fs::path again = dir / "sub" / "again.json";
    auto r = run_cli("bench '" + out.string() + "' --frames 1 --warmup 0 -q --scene-out '" + again.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(read_file(again), read_file(out)) << commands[i];
  }
}

TEST(SceneOut, NeverOverwritesAnInputNorAFileOnFailure) {
  auto dir = crowdprof::test::scratch_dir("scene_out_inputs");
  auto scene = dir / "s.json", kept = dir / "kept.json";
  std::ofstream(scene) << humanoid_scene(4, "");
  const std::string scene_text = read_file(scene);
  auto r = run_cli("bench '" + scene.string() + "' --frames 1 --warmup 0 -q --scene-out '" + scene.string() + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--scene-out"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(scene), scene_text);
  const std::string glb_text = read_file(shipped("humanoid.glb"));
  r = run_cli("bench '" + scene.string() + "' --frames 1 --warmup 0 -q --scene-out '" + shipped("humanoid.glb") + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("refusing to overwrite"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(shipped("humanoid.glb")), glb_text);
  // A run that fails leaves an existing file as it was.
  std::ofstream(kept) << "earlier";
  r = run_cli("bench '" + scene.string() + "' --action fly --frames 1 --warmup 0 -q --scene-out '" + kept.string() +
              "'");
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(read_file(kept), "earlier");
  // What a scene cannot hold is said.
  r = run_cli("bench '" + scene.string() + "' --fps 30 --frames 1 --warmup 0 -q --scene-out '" + kept.string() + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("not --fps: give them again"), std::string::npos) << r.err;
  EXPECT_EQ(crowdprof::load_scene_file(kept.string()).characters.size(), 1u);
}

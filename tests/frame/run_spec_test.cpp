// A run's settings resolve in one visible order: the defaults, the scene file,
// a baseline being re-run, the command line; later layers win, a mode brings
// its own switches, and a bad value is said by setting name (the command
// line's) or by the file it came from (a scene's or a baseline's).
#include <gtest/gtest.h>

#include "base/errors.h"
#include "frame/bench_setup.h"
#include "frame/run_spec.h"
#include "result/result.h"
#include "base/switch_table.h"
#include "scene/scene_file.h"
#include "test_support.h"

namespace {

using namespace crowdprof;
using nlohmann::json;
using Source = SpecLayer::Source;

SpecLayer layer(Source source, std::map<std::string, std::string> values, std::string path = "") {
  return SpecLayer{source, std::move(path), std::move(values)};
}

TEST(RunSpec, TheDefaultsAreBenchs) {
  RunSpec spec = resolve_run_spec({});
  EXPECT_EQ(spec.characters, 160u);
  EXPECT_EQ(spec.frames, 120u);
  EXPECT_EQ(spec.warmup, 10u);
  EXPECT_EQ(spec.mode, "threaded");
  EXPECT_EQ(spec.mode_name(), "threaded");
  EXPECT_EQ(spec.backend, "none");
  EXPECT_TRUE(spec.mode_switches() == find_mode("threaded")->switches);
}

TEST(RunSpec, LaterLayersWin) {
  std::vector<SpecLayer> layers = {layer(Source::SceneFile, {{"characters", "80"}, {"seed", "7"}}, "s.json"),
                                   layer(Source::Baseline, {{"characters", "40"}, {"frames", "30"}}, "b.json"),
                                   layer(Source::CommandLine, {{"characters", "4"}})};
  RunSpec spec = resolve_run_spec(layers);
  EXPECT_EQ(spec.characters, 4u);
  EXPECT_EQ(spec.frames, 30u);
  EXPECT_EQ(spec.seed, 7u);
}

TEST(RunSpec, AModeBringsItsOwnSwitches) {
  std::vector<SpecLayer> layers = {layer(Source::Baseline, {{"mode", "threaded"}, {"culling", "off"}}, "b.json"),
                                   layer(Source::CommandLine, {{"mode", "master"}})};
  RunSpec spec = resolve_run_spec(layers);
  EXPECT_TRUE(spec.mode_switches() == find_mode("master")->switches);
  EXPECT_EQ(spec.mode_name(), "master");
  // Without a mode on the command line, its switches add to the baseline's.
  layers[1] = layer(Source::CommandLine, {{"share", "on"}});
  spec = resolve_run_spec(layers);
  EXPECT_FALSE(spec.mode_switches().animation_culling);
  EXPECT_TRUE(spec.mode_switches().share_poses);
  EXPECT_EQ(spec.mode_name(), "threaded+custom");
  // An override that repeats the preset leaves it the preset.
  spec = resolve_run_spec(std::vector{layer(Source::CommandLine, {{"mode", "culled"}, {"culling", "on"}})});
  EXPECT_EQ(spec.mode_name(), "culled");
}

TEST(RunSpec, RecordedThreadsApplyOnlyToParallelModes) {
  std::vector<SpecLayer> layers = {layer(Source::Baseline, {{"mode", "threaded"}, {"threads", "2"}}, "b.json"),
                                   layer(Source::CommandLine, {{"mode", "master"}})};
  EXPECT_EQ(resolve_run_spec(layers).threads, 0);
  layers[1] = layer(Source::CommandLine, {});
  EXPECT_EQ(resolve_run_spec(layers).threads, 2);
  // Asked for on the command line, threads in a one-thread mode are an error.
  RunSpec spec = resolve_run_spec(std::vector{layer(Source::CommandLine, {{"mode", "master"}, {"threads", "4"}})});
  try {
    validate_run_spec(spec);
    FAIL() << "threads in master were accepted";
  } catch (const SettingError& e) {
    EXPECT_EQ(e.name, "threads");
    EXPECT_NE(e.why.find("one thread"), std::string::npos);
  }
}

TEST(RunSpec, AnActionOverAScenesActionsMeansShared) {
  std::vector<SpecLayer> layers = {layer(Source::SceneFile, {{"actions", "scene"}}, "s.json"),
                                   layer(Source::CommandLine, {{"action", "wave"}})};
  RunSpec spec = resolve_run_spec(layers);
  EXPECT_EQ(spec.actions, "shared");
  EXPECT_EQ(spec.action, "wave");
  // Over a baseline's random actions too: the action is never dropped.
  layers = {layer(Source::Baseline, {{"actions", "random"}}, "base.json"),
            layer(Source::CommandLine, {{"action", "wave"}})};
  spec = resolve_run_spec(layers);
  EXPECT_EQ(spec.actions, "shared");
  EXPECT_EQ(spec.action, "wave");
}

TEST(RunSpec, BadValuesNameTheSettingOrTheFile) {
  auto setting_error = [](std::map<std::string, std::string> values) -> SettingError {
    try {
      resolve_run_spec(std::vector{layer(Source::CommandLine, std::move(values))});
    } catch (const SettingError& e) {
      return e;
    }
    ADD_FAILURE() << "accepted";
    return SettingError("", "", "");
  };
  EXPECT_EQ(setting_error({{"characters", "0"}}).why, "a crowd needs at least 1 copy");
  EXPECT_EQ(setting_error({{"characters", "many"}}).name, "characters");
  EXPECT_EQ(setting_error({{"frames", "0"}}).name, "frames");
  EXPECT_EQ(setting_error({{"warmup", "-1"}}).why, "cannot be negative");
  EXPECT_EQ(setting_error({{"fps", "0"}}).name, "fps");
  EXPECT_EQ(setting_error({{"resolution", "160"}}).why, "expected WIDTHxHEIGHT, e.g. 1600x900");
  EXPECT_EQ(setting_error({{"backend", "vulkan"}}).name, "backend");
  EXPECT_EQ(setting_error({{"mode", "fastest"}}).name, "mode");
  EXPECT_EQ(setting_error({{"culling", "maybe"}}).why, "expected on or off");
  // One action for every copy beside a choice per copy: neither is dropped.
  EXPECT_EQ(setting_error({{"actions", "random"}, {"action", "wave"}}).name, "action");
  EXPECT_EQ(
      resolve_run_spec(std::vector{layer(Source::CommandLine, {{"actions", "shared"}, {"action", "wave"}})}).action,
      "wave");
  // Not the command line's fault: the baseline's, by its path.
  try {
    resolve_run_spec(std::vector{layer(Source::Baseline, {{"frames", "0"}}, "base.json")});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("base.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot make"), std::string::npos) << e.what();
  }
}

TEST(RunSpec, ASceneFileIsALayerUnderTheCommandLine) {
  std::string scene = (test::source_dir() / "scenes" / "thesis.json").string();
  std::vector<SpecLayer> layers = run_layers(layer(Source::CommandLine, {{"file", scene}, {"seed", "9"}}));
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_EQ(layers[0].source, Source::SceneFile);
  RunSpec spec = resolve_run_spec(layers);
  EXPECT_EQ(spec.characters, 160u);  // the scene's
  EXPECT_EQ(spec.seed, 9u);          // the command line's
  EXPECT_EQ(spec.actions, "scene");
  EXPECT_EQ(spec.file, scene);
}

TEST(RunSpec, AResultRecordsEnoughToRunItAgain) {
  Result result;
  result.samples.frame_ms.assign(30, 1.0);
  RunDescription& run = result.run;
  run.warmup = 2;
  run.fps = 60.0;
  run.mode = "threaded+custom";
  run.threads = 2;
  run.switches = find_mode("threaded")->switches;
  run.switches.share_poses = true;
  run.backend = "none";
  run.file = "hero.glb";
  run.characters = 12;
  run.action_choice = "shared";
  run.action = "dance";
  run.seed = 1;
  run.camera = "default";
  run.resolution = "640x360";
  run.actions = 3;
  run.lens = LensRecord{50.0, 32.0, 18.0, "auto"};
  RunSpec spec = resolve_run_spec(std::vector{recorded_layer(result, "b.json", "hero.glb")});
  EXPECT_EQ(spec.file, "hero.glb");
  EXPECT_EQ(spec.characters, 12u);
  EXPECT_EQ(spec.frames, 30u);
  EXPECT_EQ(spec.warmup, 2u);
  EXPECT_EQ(spec.action, "dance");
  EXPECT_EQ(spec.threads, 2);
  EXPECT_EQ(spec.resolution, "640x360");
  EXPECT_DOUBLE_EQ(spec.lens, 50.0);
  EXPECT_TRUE(spec.mode_switches().share_poses);
  EXPECT_EQ(spec.mode_name(), "threaded+custom");
  EXPECT_FALSE(spec.allow_static);
}

}  // namespace

// Animation layers on a crowd (issue 56, --anim-layer): master, culled and
// threaded compute the same layered poses on any thread count, with and
// without fades; a layer changes the poses and a layer of weight 0 does not;
// the layers' actions are counted; exact modes draw layered copies exactly;
// names a character lacks are usage errors that list its own.
#include <gtest/gtest.h>

#include <string>

#include "base/errors.h"
#include "frame/crowd_bench.h"
#include "asset/gltf_loader.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

BenchConfig layered(const std::string& mode, const std::string& layers, int threads = 2, double transitions = 0) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  EXPECT_EQ("", parse_anim_layers(layers, &config.mode.anim_layers)) << layers;
  config.mode.transitions_s = transitions;
  config.mode.blend_in_s = transitions > 0 ? 0.4 : 0.25;
  config.mode_name = mode;
  config.threads = threads;
  config.crowd.copies = 30;
  config.crowd.actions = ActionChoice::Random;
  return config;
}

std::string digest_after(const BenchConfig& config, int frames = 40) {
  CrowdBench bench(test::default_humanoid(), config);
  for (int f = 0; f < frames; ++f) bench.step();
  return bench.digest();
}

const char* kWaveOverSpine = "action=wave,mask=spine_03,falloff=2;action=walk,blend=add,weight=0.3";

}  // namespace

TEST(AnimLayers, EveryCpuModeComputesTheSameLayeredPosesOnAnyThreadCount) {
  for (double transitions : {0.0, 1.0}) {
    std::string digest;
    for (const char* mode : {"master", "culled", "threaded"})
      for (int threads : {1, 2}) {
        if (std::string(mode) != "threaded" && threads == 2) continue;
        const std::string d = digest_after(layered(mode, kWaveOverSpine, threads, transitions), 80);
        if (digest.empty()) digest = d;
        EXPECT_EQ(d, digest) << mode << " on " << threads << " threads, transitions " << transitions;
      }
  }
}

TEST(AnimLayers, ALayerChangesThePosesAndALayerOfWeightZeroDoesNot) {
  const std::string plain = digest_after(layered("threaded", ""));
  EXPECT_NE(digest_after(layered("threaded", kWaveOverSpine)), plain);
  EXPECT_EQ(digest_after(layered("threaded", "action=wave,mask=spine_03,weight=0")), plain);
}

TEST(AnimLayers, TheLayersActionsAreSampledAndEveryPoseBlended) {
  CrowdBench bench(test::default_humanoid(), layered("threaded", kWaveOverSpine));
  const Counters c = bench.step().counters;
  ASSERT_GT(c.poses_updated, 0u);
  EXPECT_EQ(c.actions_sampled, 3 * c.poses_updated) << "its own action and two layers' a pose";
  EXPECT_EQ(c.layers, 2 * c.poses_updated);
  EXPECT_EQ(c.joints_blended, c.poses_updated * test::default_humanoid().skeleton.joint_count());
}

TEST(AnimLayers, ExactModesDrawLayeredCopiesExactly) {
  for (double transitions : {0.0, 1.0}) {
    CrowdBench bench(test::default_humanoid(), layered("threaded", kWaveOverSpine, 2, transitions));
    for (int f = 0; f < 80; ++f) bench.step();
    const DrawnErrorRecord error = bench.measure_drawn_error(900);
    EXPECT_GT(error.copies_checked, 0u);
    EXPECT_EQ(error.max, 0.0) << "the reference lays the same layers, transitions " << transitions;
  }
}

TEST(AnimLayers, AnActionOrJointTheCharacterLacksIsAUsageErrorListingItsOwn) {
  try {
    CrowdBench bench(test::default_humanoid(), layered("threaded", "action=jump"));
    FAIL() << "no action jump";
  } catch (const UsageError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no action 'jump'"), std::string::npos) << what;
    EXPECT_NE(what.find("dance, walk, wave"), std::string::npos) << what;
  }
  try {
    CrowdBench bench(test::default_humanoid(), layered("threaded", "action=wave,mask=Spine"));
    FAIL() << "no joint Spine";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("no joint 'Spine' (the joints are hips, spine_01"), std::string::npos)
        << e.what();
  }
}

// The docs' worked example: the Fox walks with Survey on its front half.
TEST(AnimLayers, TheFoxWalksWithSurveyOverItsSpineInEveryCpuMode) {
  CROWDPROF_REQUIRE_SAMPLES();
  const Character fox = load_character(test::sample("Fox/glTF-Binary/Fox.glb"));
  std::string digest;
  for (const char* mode : {"master", "threaded"}) {
    BenchConfig config = layered(mode, "action=Survey,mask=b_Spine01_02,falloff=1");
    config.crowd.actions = ActionChoice::Shared;
    config.crowd.shared_action = 1;  // Walk (Survey, Walk, Run)
    CrowdBench bench(fox, config);
    for (int f = 0; f < 30; ++f) bench.step();
    if (digest.empty()) digest = bench.digest();
    EXPECT_EQ(bench.digest(), digest) << mode;
    EXPECT_EQ(bench.measure_drawn_error(900).max, 0.0) << mode;
  }
}

TEST(AnimLayers, TheSwitchReadsBackAsWritten) {
  std::vector<AnimLayer> layers;
  ASSERT_EQ("", parse_anim_layers("blend=add,action=walk,weight=0.25\naction=wave,mask=spine_01,falloff=3", &layers));
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_EQ(layers[0].blend, LayerBlend::Add);
  EXPECT_EQ(layers[1].falloff, 3);
  const std::string text = anim_layers_text(layers);
  EXPECT_EQ(text,
            "action=walk,weight=0.25,falloff=0,blend=add;action=wave,mask=spine_01,weight=1,falloff=3,blend=override");
  std::vector<AnimLayer> back;
  ASSERT_EQ("", parse_anim_layers(text, &back));
  EXPECT_EQ(back, layers);
  for (const char* bad : {"mask=spine_01", "action=wave,weight=2", "action=wave,blend=mix", "action=wave,speed=2",
                          "action=wave,falloff=1.5", "wave"})
    EXPECT_NE("", parse_anim_layers(bad, &back)) << bad;
}

// The switch table is the one place a switch is declared: every preset's
// switches survive the trip through text and through a result's JSON, values
// are checked in the library's own terms, and a result's switches read back
// as the same ModeSwitches (older results, without later switches, included).
#include <gtest/gtest.h>

#include "base/switch_table.h"

namespace {

using namespace crowdprof;
using nlohmann::json;

TEST(SwitchTable, EveryPresetSurvivesTextAndJson) {
  for (const ModePreset& preset : mode_presets()) {
    ModeSwitches from_text;
    for (const SwitchSpec& spec : switch_table())
      EXPECT_EQ(spec.set(from_text, switch_text(spec, preset.switches)), "") << preset.name << " " << spec.name;
    EXPECT_TRUE(from_text == preset.switches) << preset.name;
    ModeSwitches from_json;
    EXPECT_EQ(switches_from_json(switches_to_json(preset.switches), from_json), "") << preset.name;
    EXPECT_TRUE(from_json == preset.switches) << preset.name;
  }
}

TEST(SwitchTable, EverySwitchChangesTheSwitches) {
  // A switch whose setter wrote nothing (or the wrong field) would leave
  // ModeSwitches as it was for one of these values.
  const std::map<std::string, std::string> other = {{"lookups", "string"},
                                                    {"culling", "on"},
                                                    {"pose", "shared"},
                                                    {"parallel", "on"},
                                                    {"skinning", "gpu"},
                                                    {"palettes", "buffer"},
                                                    {"draw", "instanced"},
                                                    {"vertex_format", "packed"},
                                                    {"share", "on"},
                                                    {"share_quantum", "1/30"},
                                                    {"update_lod", "on"},
                                                    {"lod_thresholds", "0.5,0.25,0.1"},
                                                    {"anim_budget", "2"},
                                                    {"passes", "3"},
                                                    {"frustum", "gpu"},
                                                    {"mesh_lod", "on"},
                                                    {"mesh_lod_thresholds", "0.5,0.25,0.1"},
                                                    {"index_order", "file"},
                                                    {"transitions", "2"},
                                                    {"blend_in", "0.5"},
                                                    {"crossfade", "frozen"},
                                                    {"anim_layer", "action=wave,weight=1,falloff=0,blend=override"}};
  ASSERT_EQ(other.size(), switch_table().size());
  for (const SwitchSpec& spec : switch_table()) {
    ModeSwitches s;
    ASSERT_TRUE(other.count(std::string(spec.name))) << spec.name;
    EXPECT_EQ(spec.set(s, other.at(std::string(spec.name))), "") << spec.name;
    EXPECT_FALSE(s == ModeSwitches{}) << spec.name;
    EXPECT_EQ(switch_text(spec, s), other.at(std::string(spec.name)) == "1/30" ? switch_text(json(1.0 / 30))
                                                                               : other.at(std::string(spec.name)));
  }
}

TEST(SwitchTable, BadValuesAreSaidWithoutTheCommandLine) {
  ModeSwitches s;
  EXPECT_EQ(find_switch("culling")->set(s, "maybe"), "expected on or off");
  EXPECT_EQ(find_switch("skinning")->set(s, "cuda"), "expected one of rasterizer, animations, gpu, compute, baked");
  EXPECT_NE(find_switch("share_quantum")->set(s, "-1"), "");
  EXPECT_NE(find_switch("lod_thresholds")->set(s, "0.1,0.2,0.3"), "");
  EXPECT_NE(find_switch("anim_budget")->set(s, "lots"), "");
  for (const char* passes : {"0", "11", "2.5", "-1", "two"})
    EXPECT_EQ(find_switch("passes")->set(s, passes).rfind("expected 1 to 10", 0), 0u) << passes;
  for (const SwitchSpec& spec : switch_table()) EXPECT_EQ(spec.set(s, "nonsense").find("--"), std::string::npos);
  EXPECT_EQ(find_switch("no_such"), nullptr);
  EXPECT_EQ(option_spelling("share_quantum"), "--share-quantum");
}

TEST(SwitchTable, ResultsRecordLaterSwitchesOnlyWhenSet) {
  json plain = switches_to_json(find_mode("threaded")->switches);
  for (const char* later : {"vertex_format", "share", "share_quantum", "update_lod", "lod_thresholds", "anim_budget"})
    EXPECT_FALSE(plain.contains(later)) << later;
  for (const char* thesis : {"lookups", "culling", "pose", "parallel", "skinning", "palettes", "draw"})
    EXPECT_TRUE(plain.contains(thesis)) << thesis;
  json budget = switches_to_json(find_mode("budget")->switches);
  EXPECT_EQ(budget["share"], true);
  EXPECT_DOUBLE_EQ(budget["anim_budget"].get<double>(), 2.0);
}

TEST(SwitchTable, AnOlderResultReadsWithTheDefaults) {
  // A result from before palettes and draw were recorded.
  json old = {
      {"lookups", "bundled"}, {"culling", true}, {"pose", "per-copy"}, {"parallel", true}, {"skinning", "animations"}};
  ModeSwitches s;
  ASSERT_EQ(switches_from_json(old, s), "");
  // It drew the file's triangles in the file's order: the default then.
  EXPECT_EQ(s.index_order, IndexOrder::File);
  s.index_order = IndexOrder::Optimized;
  EXPECT_TRUE(s == find_mode("threaded")->switches);
  EXPECT_NE(switches_from_json({{"warp", true}}, s), "");
  EXPECT_NE(switches_from_json({{"culling", "sometimes"}}, s).find("culling"), std::string::npos);
  EXPECT_NE(switches_from_json(json::array(), s), "");
  EXPECT_NE(switches_from_json({{"culling", json::array()}}, s), "");
}

TEST(SwitchTable, IndexOrderIsOptimizedForNewRunsAndRecordedAlways) {
  const ModeSwitches plain;
  EXPECT_EQ(plain.index_order, IndexOrder::Optimized);
  const json recorded = switches_to_json(plain);
  ASSERT_TRUE(recorded.contains("index_order"));
  EXPECT_EQ(recorded["index_order"], "optimized");
  ModeSwitches back;
  ASSERT_EQ(switches_from_json(recorded, back), "");
  EXPECT_TRUE(back == plain);
  ModeSwitches file;
  file.index_order = IndexOrder::File;
  ASSERT_EQ(switches_from_json(switches_to_json(file), back), "");
  EXPECT_EQ(back.index_order, IndexOrder::File);
  EXPECT_NE(switches_from_json({{"index_order", "random"}}, back).find("file, optimized"), std::string::npos);
}

TEST(SwitchTable, TransitionsHaveAFloorSoThatAFrameHoldsFewChanges) {
  ModeSwitches s;
  const SwitchSpec& transitions = *find_switch("transitions");
  EXPECT_EQ(transitions.set(s, "0"), "");
  EXPECT_EQ(transitions.set(s, "0.05"), "");
  EXPECT_NE(transitions.set(s, "0.0001").find("0.05"), std::string::npos);
  EXPECT_DOUBLE_EQ(s.transitions_s, 0.05) << "a refused value leaves the switch as it was";
}

TEST(SwitchTable, HelpNamesEveryPresetsValue) {
  std::string values = preset_values(*find_switch("culling"));
  EXPECT_EQ(values, "off in master; on in the others");
  EXPECT_EQ(preset_values(*find_switch("share")), "on in shared, budget; off in the others");
  EXPECT_EQ(preset_values(*find_switch("update_lod")), "off in every mode");
  // A fraction as a reader reads it (issue 55): 1/30 s, not 0.03333333333333333.
  EXPECT_EQ(preset_values(*find_switch("share_quantum")), "0.0333 in budget; 0 in the others");
  EXPECT_EQ(preset_values(*find_switch("anim_budget")), "2 in budget; 0 in the others");
}

// Two runs' switches as a message names them (issue 55): only those that
// differ, in the table's order, as options with readable values; not the
// whole "switches" object as JSON in alphabetical order.
TEST(SwitchTable, DifferencesAreTheSwitchesThatDifferInTheTablesOrder) {
  ModeSwitches a, b;
  EXPECT_EQ(switch_differences(a, b), (std::pair<std::string, std::string>{}));
  ASSERT_EQ(find_switch("share_quantum")->set(a, "1/30"), "");
  ASSERT_EQ(find_switch("culling")->set(a, "on"), "");
  ASSERT_EQ(find_switch("culling")->set(b, "off"), "");
  auto [ta, tb] = switch_differences(a, b);
  EXPECT_EQ(ta, "--culling on, --share-quantum 0.0333");
  EXPECT_EQ(tb, "--culling off, --share-quantum 0");
  // Apart only beyond three digits: the exact values, so that the two differ.
  ASSERT_EQ(find_switch("share_quantum")->set(b, "0.033334"), "");
  ASSERT_EQ(find_switch("culling")->set(b, "on"), "");
  std::tie(ta, tb) = switch_differences(a, b);
  EXPECT_EQ(ta, "--share-quantum 0.03333333333333333");
  EXPECT_EQ(tb, "--share-quantum 0.033334");
}

}  // namespace

namespace {

// Results before the table wrote thresholds with nine digits; they still read
// as the same switches as today's shortest text.
TEST(SwitchTable, OlderThresholdTextReadsTheSame) {
  crowdprof::ModeSwitches older, today;
  ASSERT_EQ(crowdprof::switches_from_json({{"lod_thresholds", "0.5,0.200000003,0.100000001"}}, older), "");
  ASSERT_EQ(crowdprof::switches_from_json({{"lod_thresholds", "0.5,0.2,0.1"}}, today), "");
  EXPECT_TRUE(older == today);
  EXPECT_EQ(crowdprof::switches_to_json(today)["lod_thresholds"], "0.5,0.2,0.1");
}

}  // namespace

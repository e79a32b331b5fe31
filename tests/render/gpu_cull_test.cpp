// frustum gpu (issue 30 item 1, docs/modes.md): the GPU-driven crowd. Its cull
// pass finds the copies the CPU's Scenegraph finds and draws the image the
// CPU-culled baked path draws, for one character and for two with random
// actions, with passes; what the CPU sends and submits each frame does not
// grow with the crowd; a GL without compute shaders is refused, naming it.
#include <gtest/gtest.h>

#include <string>

#include "base/modes.h"
#include "base/switch_table.h"
#include "render/gl_errors.h"
#include "render/gpu_frame_buffers.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;
using namespace crowdprof::test;

namespace {

struct CullCase {
  std::string name;
  std::vector<const Character*> characters;
  ActionChoice actions;
  uint32_t passes;
};

}  // namespace

TEST(GpuCull, FindsTheCopiesTheCpuFindsAndDrawsTheSameImage) {
  OPEN_GL_OR_SKIP(context);
  const std::vector<CullCase> cases = {
      {"humanoid, shared action", {&default_humanoid()}, ActionChoice::Shared, 1},
      {"two characters, random actions", {&default_humanoid(), &thirty_bone_humanoid()}, ActionChoice::Random, 1},
      {"two characters, prepass and a shadow cascade",
       {&default_humanoid(), &thirty_bone_humanoid()},
       ActionChoice::Random,
       3},
  };
  for (const CullCase& c : cases) {
    Shot shot;
    shot.mode = "baked";
    shot.copies = 60;  // the default camera leaves the crowd's far corners out
    shot.frame = 5;
    shot.actions = c.actions;
    shot.passes = c.passes;
    Frame cpu = render(*context, c.characters, shot);
    shot.frustum = FrustumTest::Gpu;
    Frame gpu = render(*context, c.characters, shot);
    ASSERT_GT(cpu.counters.copies_culled, 0u) << c.name << ": the camera should leave some copies out";
    ASSERT_GT(cpu.counters.copies_visible, 0u) << c.name;
    EXPECT_EQ(gpu.counters.copies_visible, cpu.counters.copies_visible) << c.name;
    EXPECT_EQ(gpu.counters.copies_culled, cpu.counters.copies_culled) << c.name;
    EXPECT_EQ(gpu.counters.poses_updated, 0u) << c.name;
    // The digest hashes each visible copy's baked record: the one the GPU made
    // is the one the CPU would have.
    EXPECT_EQ(gpu.digest, cpu.digest) << c.name;
    // The records and their order differ (the GPU appends in any order); the
    // samples, times and placements are the same, so the image is too, but
    // for copies meeting at exactly the same depth.
    size_t pixels = cpu.rgba.size() / 4;
    ASSERT_GT(covered(cpu.rgba), pixels / 200) << c.name << ": too little drawn to compare";
    size_t differing = pixels_differing(cpu.rgba, gpu.rgba, 4);
    std::cout << "[ info ] " << c.name << ": " << covered(cpu.rgba) << " pixels drawn, " << differing
              << " differ by more than 4 (" << pixels_differing(cpu.rgba, gpu.rgba, 0) << " at all)\n";
    EXPECT_LE(differing * 2000, pixels) << c.name;
  }
}

TEST(GpuCull, WhatTheCpuSendsAndSubmitsDoesNotGrowWithTheCrowd) {
  OPEN_GL_OR_SKIP(context);
  const Character* both[] = {&default_humanoid(), &thirty_bone_humanoid()};
  Shot shot;
  shot.mode = "baked";
  shot.frame = 2;
  shot.frustum = FrustumTest::Gpu;
  shot.copies = 20;
  Frame few = render(*context, both, shot);
  shot.copies = 200;
  Frame many = render(*context, both, shot);
  EXPECT_GT(many.counters.copies_visible, few.counters.copies_visible);
  // One indirect draw per character, and the two commands with their counts at zero.
  EXPECT_EQ(few.counters.draw_calls, 2u);
  EXPECT_EQ(many.counters.draw_calls, 2u);
  EXPECT_EQ(few.counters.bytes_uploaded, 2u * 20u);
  EXPECT_EQ(many.counters.bytes_uploaded, few.counters.bytes_uploaded);
  // The CPU-culled path sends a record per copy on screen.
  shot.frustum = FrustumTest::Cpu;
  Frame cpu = render(*context, both, shot);
  EXPECT_EQ(cpu.counters.bytes_uploaded, sizeof(GpuInstance) * cpu.counters.copies_visible);
}

TEST(GpuCull, AGlWithoutComputeShadersIsRefusedNamingThem) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.mode = "baked";
  shot.copies = 2;
  shot.frustum = FrustumTest::Gpu;
  shot.hide_features = "compute";
  try {
    render(*context, default_humanoid(), shot);
    FAIL() << "frustum gpu ran on a context without compute shaders";
  } catch (const GlUnavailable& e) {
    EXPECT_NE(std::string(e.what()).find("frustum gpu needs compute shaders"), std::string::npos) << e.what();
  }
}

// The pass reads the copies (64 bytes each) and writes their records (16 a
// mesh level) as storage blocks: a crowd past one block is refused at load,
// naming the limit and how many copies fit (64 KiB: 1,024).
TEST(GpuCull, ACrowdPastAStorageBlockIsRefusedSayingHowManyFit) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.mode = "baked";
  shot.copies = 1100;
  shot.frustum = FrustumTest::Gpu;
  shot.bake_rate = 5.0f;  // a table that fits 64 KiB
  shot.hide_features = "small-blocks";
  try {
    render(*context, thirty_bone_humanoid(), shot);
    FAIL() << "1100 copies' records and boxes were bound past a 64 KiB block";
  } catch (const GlUnavailable& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << what;
    EXPECT_NE(what.find("room for 1024 copies, not 1100"), std::string::npos) << what;
    EXPECT_NE(what.find("frustum cpu"), std::string::npos) << what;
  }
  shot.copies = 500;  // fits: drawn
  EXPECT_GT(render(*context, thirty_bone_humanoid(), shot).counters.copies_visible, 0u);
}

TEST(GpuCull, IsASwitchThatNeedsBakedSkinning) {
  ModeSwitches s = find_mode("baked")->switches;
  EXPECT_EQ(switch_text(*find_switch("frustum"), s), "cpu");
  ASSERT_EQ(find_switch("frustum")->set(s, "gpu"), "");
  EXPECT_EQ(s.frustum, FrustumTest::Gpu);
  EXPECT_EQ(conflicts(s).str(), "");
  EXPECT_EQ(switches_to_json(s).at("frustum"), "gpu");
  EXPECT_NE(find_switch("frustum")->set(s, "fast").find("expected one of cpu, gpu"), std::string::npos);
  for (const char* mode : {"instanced", "compute", "threaded"}) {
    ModeSwitches other = find_mode(mode)->switches;
    other.frustum = FrustumTest::Gpu;
    EXPECT_NE(conflicts(other).marked().find("{frustum} gpu"), std::string::npos) << mode;
    EXPECT_NE(conflicts(other).marked().find("{skinning} baked"), std::string::npos) << mode;
  }
  // Results made before the switch read as frustum cpu.
  EXPECT_FALSE(switches_to_json(find_mode("baked")->switches).contains("frustum"));
}

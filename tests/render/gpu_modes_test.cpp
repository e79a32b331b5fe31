// The modes beyond the thesis (docs/modes.md): palettes in a shader storage
// buffer and instanced drawing. Their switches are data; each draws the image
// CPU skinning draws; a 300-bone character runs in them with no fallback; their
// counters are exact; a GL without what they need is refused, never drawn black.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "base/modes.h"
#include "gen/humanoid.h"
#include "render/gl_features.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;
using namespace crowdprof::test;

namespace {

const Character& humanoid300() {
  static const Character character = generate_humanoid({300, 3000, 1});
  return character;
}

// "Today's tolerance": at most 0.05% of the frame's pixels differ from CPU
// skinning by more than 4 levels (the two sum the same matrices in different
// orders, so an edge may move by a pixel).
void expect_same_image(const Frame& cpu, const Frame& gpu, const std::string& what) {
  size_t pixels = cpu.rgba.size() / 4;
  ASSERT_GT(covered(cpu.rgba), pixels / 200) << what << ": too little drawn to compare";
  size_t differing = pixels_differing(cpu.rgba, gpu.rgba, 4);
  std::cout << "[ info ] " << what << ": " << covered(cpu.rgba) << " pixels drawn, " << differing
            << " differ by more than 4 (" << pixels_differing(cpu.rgba, gpu.rgba, 0) << " at all)\n";
  EXPECT_LE(differing * 2000, pixels) << what;
  EXPECT_GT(covered(gpu.rgba), pixels / 200) << what << ": nothing drawn";
}

constexpr const char* kNewModes[] = {"buffer", "instanced"};

}  // namespace

TEST(GpuModes, ThesisPresetsAreUnchangedAndTheNewOnesAreSwitches) {
  std::vector<std::string> names;
  for (const ModePreset& p : mode_presets()) names.emplace_back(p.name);
  ASSERT_GE(names.size(), 6u);
  EXPECT_EQ(std::vector<std::string>(names.begin(), names.begin() + 6),
            (std::vector<std::string>{"master", "culled", "threaded", "hwskin", "buffer", "instanced"}));
  for (const char* thesis : {"master", "culled", "threaded", "hwskin"}) {
    EXPECT_EQ(find_mode(thesis)->switches.palettes, PaletteStorage::Uniforms) << thesis;
    EXPECT_EQ(find_mode(thesis)->switches.draw, DrawMethod::PerCopy) << thesis;
  }
  ModeSwitches buffer = find_mode("hwskin")->switches;
  buffer.palettes = PaletteStorage::Buffer;
  EXPECT_EQ(find_mode("buffer")->switches, buffer);
  ModeSwitches instanced = buffer;
  instanced.draw = DrawMethod::Instanced;
  EXPECT_EQ(find_mode("instanced")->switches, instanced);
  EXPECT_EQ(conflicts(buffer).str(), "");
  EXPECT_EQ(conflicts(instanced).str(), "");
}

TEST(GpuModes, SwitchesThatCannotWorkTogetherAreRefused) {
  ModeSwitches s = find_mode("instanced")->switches;
  s.palettes = PaletteStorage::Uniforms;
  EXPECT_NE(conflicts(s).str().find("palettes buffer"), std::string::npos) << conflicts(s).str();
  // The library names the switch as results spell it; cli/ spells the option.
  EXPECT_EQ(conflicts(s).str().find("--"), std::string::npos) << conflicts(s).str();
  EXPECT_NE(conflicts(s).marked().find("{palettes} buffer"), std::string::npos) << conflicts(s).marked();
  s = find_mode("threaded")->switches;
  s.palettes = PaletteStorage::Buffer;
  EXPECT_NE(conflicts(s).str().find("skinning gpu"), std::string::npos) << conflicts(s).str();
  s = find_mode("threaded")->switches;
  s.draw = DrawMethod::Instanced;
  EXPECT_NE(conflicts(s).str().find("skinning gpu"), std::string::npos) << conflicts(s).str();
}

TEST(GpuModes, DrawTheImageCpuSkinningDraws) {
  OPEN_GL_OR_SKIP(context);
  std::vector<std::pair<std::string, const Character*>> characters = {{"humanoid", &default_humanoid()},
                                                                      {"humanoid-300", &humanoid300()}};
  std::vector<std::unique_ptr<Character>> samples;
  if (have_samples()) {
    for (const char* file : {"Fox/glTF-Binary/Fox.glb", "CesiumMan/glTF-Binary/CesiumMan.glb"}) {
      samples.push_back(std::make_unique<Character>(load_character(sample(file))));
      characters.emplace_back(file, samples.back().get());
    }
  } else {
    std::cout << "[ info ] sample characters not found at " << samples_dir().string()
              << ": checking the generated humanoids only\n";
  }
  for (const auto& [name, character] : characters) {
    Shot shot;
    shot.copies = 8;
    shot.camera = "close";  // a few copies filling the frame
    Frame cpu = render(*context, *character, shot);
    ASSERT_FALSE(cpu.gpu_skinned);
    for (const char* mode : kNewModes) {
      shot.mode = mode;
      Frame gpu = render(*context, *character, shot);
      EXPECT_TRUE(gpu.gpu_skinned) << name << " " << mode;
      EXPECT_EQ(gpu.counters.copies_fallback, 0u) << name << " " << mode;
      expect_same_image(cpu, gpu, name + " in mode " + mode);
    }
  }
}

TEST(GpuModes, ACrowdWithRandomActionsAndTwoCharactersDrawsTheSameImage) {
  OPEN_GL_OR_SKIP(context);
  const Character* both[] = {&default_humanoid(), &humanoid300()};
  Shot shot;
  shot.copies = 12;
  shot.frame = 9;
  shot.actions = ActionChoice::Random;
  Frame cpu = render(*context, both, shot);
  for (const char* mode : kNewModes) {
    shot.mode = mode;
    Frame gpu = render(*context, both, shot);
    EXPECT_TRUE(gpu.gpu_skinned) << mode;
    expect_same_image(cpu, gpu, std::string("random actions, two characters, mode ") + mode);
  }
  shot.mode = "instanced";
  Frame instanced = render(*context, both, shot);
  EXPECT_EQ(instanced.counters.draw_calls, 2u) << "one instanced draw per character kind";
}

TEST(GpuModes, BufferPalettesDrawAsTheUniformArrayDoes) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.mode = "hwskin";
  Frame uniforms = render(*context, default_humanoid(), shot);
  for (const char* mode : kNewModes) {
    shot.mode = mode;
    Frame buffer = render(*context, default_humanoid(), shot);
    // The same matrices in the same order: the same digest, and the image within a shade.
    EXPECT_EQ(buffer.digest, uniforms.digest) << mode;
    EXPECT_LE(pixels_differing(uniforms.rgba, buffer.rgba, 1), uniforms.rgba.size() / 4 / 2000) << mode;
  }
}

TEST(GpuModes, A300BoneCharacterRunsInTheBufferModesAndHwskinFallsBack) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.copies = 6;
  shot.camera = "all";
  shot.mode = "hwskin";
  Frame hwskin = render(*context, humanoid300(), shot);
  EXPECT_FALSE(hwskin.gpu_skinned);
  EXPECT_EQ(hwskin.counters.copies_fallback, 6u);
  EXPECT_EQ(hwskin.counters.vertices_skinned, 6u * 3000);
  for (const char* mode : kNewModes) {
    shot.mode = mode;
    Frame f = render(*context, humanoid300(), shot);
    EXPECT_TRUE(f.gpu_skinned) << mode;
    EXPECT_EQ(f.counters.copies_fallback, 0u) << mode;
    EXPECT_EQ(f.counters.vertices_skinned, 0u) << mode;
  }
}

TEST(GpuModes, CountersAreExact) {
  OPEN_GL_OR_SKIP(context);
  const Character& c = default_humanoid();
  const uint64_t palette = c.skeleton.joint_count() * 48;  // 3 rows of 4 floats per joint
  EXPECT_EQ(palette, 3312u);
  for (size_t copies : {size_t{8}, size_t{40}}) {
    Shot shot;
    shot.copies = copies;
    shot.frame = 1;
    shot.mode = "hwskin";
    Frame hwskin = render(*context, c, shot);
    EXPECT_EQ(hwskin.counters.gpu_palette_bytes, 128u * 48) << "the uniform array of 128 bones";
    shot.mode = "buffer";
    Frame buffer = render(*context, c, shot);
    uint64_t visible = buffer.counters.copies_visible;
    EXPECT_GT(visible, 0u);
    if (copies == 40) {
      EXPECT_LT(visible, copies) << "the default camera leaves some copies out";
    }
    EXPECT_EQ(buffer.counters.draw_calls, visible);
    EXPECT_EQ(buffer.counters.bytes_uploaded, visible * (palette + 64));
    EXPECT_EQ(buffer.counters.palette_bytes_uploaded, visible * palette);
    EXPECT_EQ(buffer.counters.record_bytes_uploaded, visible * 64) << "a model matrix a draw";
    EXPECT_EQ(buffer.counters.gpu_palette_bytes, copies * palette) << "room for every copy's palette";
    shot.mode = "instanced";
    Frame instanced = render(*context, c, shot);
    EXPECT_EQ(instanced.counters.copies_visible, visible);
    EXPECT_EQ(instanced.counters.draw_calls, 1u) << "one draw for all " << visible << " copies on screen";
    // Frame 1: the placements went up in frame 0; a 16-byte record a copy on screen.
    EXPECT_EQ(instanced.counters.bytes_uploaded, visible * (palette + 16));
    EXPECT_EQ(instanced.counters.palette_bytes_uploaded, visible * palette);
    EXPECT_EQ(instanced.counters.record_bytes_uploaded, visible * 16);
    // Room for every copy's palette and record, and its placement (48 bytes).
    EXPECT_EQ(instanced.counters.gpu_palette_bytes, copies * (palette + 16 + 48));
    // CPU skinning keeps no palette on the GPU.
    shot.mode = "threaded";
    EXPECT_EQ(render(*context, c, shot).counters.gpu_palette_bytes, 0u);
  }
}

TEST(GpuModes, AGlWithoutVertexStorageBuffersIsRefusedNamingIt) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.hide_features = "vertex-ssbo";
  shot.mode = "hwskin";  // needs no storage buffer: still draws
  EXPECT_TRUE(render(*context, default_humanoid(), shot).gpu_skinned);
  for (const char* mode : kNewModes) {
    shot.mode = mode;
    try {
      render(*context, default_humanoid(), shot);
      FAIL() << mode << " ran without shader storage buffers";
    } catch (const GlUnavailable& e) {
      EXPECT_NE(std::string(e.what()).find("no shader storage buffers in the vertex stage"), std::string::npos)
          << e.what();
    }
  }
}

TEST(GpuModes, UnknownFeaturesToHideAreRefused) {
  OPEN_GL_OR_SKIP(context);
  EXPECT_THROW(read_gl_features("vertex-ssbo,warp-drive"), UsageError);
  GlFeatures f = read_gl_features("timer-query, vertex-ssbo");
  EXPECT_FALSE(f.storage_buffers());
  EXPECT_FALSE(f.timer_queries());
  GlFeatures real = read_gl_features();
  std::cout << "[ info ] vertex storage blocks " << real.vertex_storage_blocks << ", largest block "
            << real.max_storage_block_bytes << " bytes, timer bits " << real.timer_bits << "\n";
}

TEST(GpuModesCli, AMissingFeatureIsOneLineAndExit4) {
  if (!have_gl()) GTEST_SKIP() << "no GL backend on this machine";
  std::string scene = (source_dir() / "scenes" / "humanoid.glb").string();
  setenv("CROWDPROF_GL_HIDE", "vertex-ssbo", 1);
  auto refused =
      run_cli("bench '" + scene + "' -n 2 --mode instanced --backend auto --resolution 160x90 --frames 1 --warmup 0");
  auto hwskin =
      run_cli("bench '" + scene + "' -n 2 --mode hwskin --backend auto --resolution 160x90 --frames 1 --warmup 0");
  unsetenv("CROWDPROF_GL_HIDE");
  EXPECT_EQ(refused.status, 4) << refused.err;
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  EXPECT_NE(refused.err.find("no shader storage buffers in the vertex stage"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.out, "") << "nothing reported as measured";
  EXPECT_EQ(hwskin.status, 0) << hwskin.err;
}

TEST(GpuModesCli, SwitchesOnTheCommandLine) {
  std::string scene = (source_dir() / "scenes" / "humanoid.glb").string();
  auto r = run_cli("bench '" + scene + "' -n 2 --mode threaded --draw instanced --frames 1 --warmup 0");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--skinning gpu"), std::string::npos) << r.err;
  r = run_cli("bench '" + scene + "' -n 2 --palettes ssbo --frames 1 --warmup 0");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--palettes 'ssbo': expected one of uniforms, buffer"), std::string::npos) << r.err;
}

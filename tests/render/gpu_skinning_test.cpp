// Skinning compute and baked (issue 12, docs/modes.md): each draws what CPU
// skinning draws (baked within the tolerance its measured deviation allows),
// for the humanoid, a 300-bone humanoid, a crowd with random actions, Fox and
// CesiumMan; their counters and GPU memory are exact; a GL without what they
// need is refused in one line, never drawn black.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "animation/bake.h"
#include "asset/gltf_loader.h"
#include "frame/crowd_bench.h"
#include "gen/humanoid.h"
#include "render/crowd_renderer.h"
#include "render/gl_errors.h"
#include "render/gpu_frame_buffers.h"
#include "render/gpu_placements.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;
using namespace crowdprof::test;

namespace {

const Character& bony() {  // crowdprof gen --bones 300 --vertices 2000: over hwskin's 128
  static const Character character = [] {
    HumanoidOptions options;
    options.bones = 300;
    options.vertices = 2000;
    return generate_humanoid(options);
  }();
  return character;
}

struct Subject {
  std::string name;
  const Character* character;
  bool random_actions = false;
};

std::vector<Subject> subjects(std::vector<Character>& loaded) {
  std::vector<Subject> list = {
      {"humanoid", &default_humanoid()}, {"300 bones", &bony()}, {"random actions", &default_humanoid(), true}};
  if (test::have_samples()) {
    loaded.push_back(load_character(test::sample("Fox/glTF-Binary/Fox.glb")));
    loaded.push_back(load_character(test::sample("CesiumMan/glTF-Binary/CesiumMan.glb")));
    list.push_back({"Fox", &loaded[0]});
    list.push_back({"CesiumMan", &loaded[1]});
  } else {
    std::cout << "[ info ] sample characters not found: Fox and CesiumMan skipped\n";
  }
  return list;
}

// Pixels the crowd of `software` may change when its vertices move by up to
// `deviation` model units. On screen a vertex then moves by at most deviation x
// (pixels per unit at the nearest copy) = r pixels; an outline moved by r
// pixels changes about r pixels per pixel of its length. So the tolerance is
// 0.05% of the frame (as for the exact modes) plus the exact picture's outline
// pixels times r.
size_t baked_tolerance(const Frame& software, const CrowdBench& bench, float deviation, float* reach_px) {
  float pixels_per_unit = 0.0f;
  for (size_t i = 0; i < bench.crowd().size(); ++i) {
    glm::vec4 centre = bench.camera().view_projection() * (bench.crowd().world[i] * glm::vec4(0, 0, 0, 1));
    // Half the frame's height spans clip y of w: a unit at depth w spans height / 2 x P[1][1] / w pixels.
    if (centre.w > 0)
      pixels_per_unit = std::max(pixels_per_unit, kHeight / 2.0f * bench.camera().projection()[1][1] / centre.w);
  }
  size_t edges = 0;
  for (int y = 0; y + 1 < kHeight; ++y)
    for (int x = 0; x + 1 < kWidth; ++x) {
      size_t p = static_cast<size_t>(y) * kWidth + static_cast<size_t>(x);
      edges += is_background(software.rgba, p) != is_background(software.rgba, p + 1) ||
               is_background(software.rgba, p) != is_background(software.rgba, p + kWidth);
    }
  *reach_px = deviation * pixels_per_unit;
  return software.rgba.size() / 4 * 5 / 10000 + static_cast<size_t>(static_cast<float>(edges) * *reach_px);
}

}  // namespace

// Compute skinning is exact: within 0.05% of the frame of CPU skinning. Baked
// is within the tolerance its measured deviation allows (baked_tolerance).
TEST(GpuSkinning, ComputeAndBakedDrawWhatCpuSkinningDraws) {
  OPEN_GL_OR_SKIP(context);
  std::vector<Character> loaded;
  for (const Subject& subject : subjects(loaded)) {
    Shot shot;
    if (subject.random_actions) shot.actions = ActionChoice::Random;
    shot.copies = subject.random_actions ? 24 : 8;
    Frame software = render(*context, *subject.character, shot);
    size_t pixels = software.rgba.size() / 4, drawn = covered(software.rgba);
    ASSERT_GT(drawn, pixels / 200) << subject.name;
    for (const char* mode : {"compute", "baked"}) {
      shot.mode = mode;
      shot.bake_rate = kDefaultBakeRateHz;
      Frame gpu = render(*context, *subject.character, shot);
      EXPECT_TRUE(gpu.gpu_skinned) << subject.name << " " << mode;
      EXPECT_EQ(gpu.counters.copies_fallback, 0u) << subject.name << " " << mode;
      EXPECT_GT(covered(gpu.rgba), drawn * 9 / 10) << subject.name << " " << mode << ": not a black image";
      size_t differing = pixels_differing(software.rgba, gpu.rgba, 4), tolerance = pixels * 5 / 10000;
      std::string deviation;
      if (std::string(mode) == "baked") {
        // The deviation as a bench of this character measures it at load.
        RendererConfig rc;
        rc.width = kWidth;
        rc.height = kHeight;
        GlCrowdRenderer renderer(*context, *subject.character, shot.copies, rc);
        BenchConfig config;
        config.mode = find_mode("baked")->switches;
        config.crowd.copies = shot.copies;
        config.aspect = static_cast<float>(kWidth) / kHeight;
        config.renderer = &renderer;
        CrowdBench bench(*subject.character, config);
        float reach = 0.0f;
        tolerance = baked_tolerance(software, bench, bench.bake_summary().max_deviation, &reach);
        deviation = " (deviation " + std::to_string(bench.bake_summary().max_deviation) + " units, " +
                    std::to_string(100 * bench.bake_summary().max_deviation_fraction) + "% of height, " +
                    std::to_string(reach) + " px)";
      }
      std::cout << "[ info ] " << subject.name << " " << mode << deviation << ": of " << drawn << " pixels drawn, "
                << differing << " differ by more than 4; tolerance " << tolerance << "\n";
      EXPECT_LE(differing, tolerance) << subject.name << " " << mode;
    }
  }
}

TEST(GpuSkinning, ComputeAndBakedCountWhatTheySend) {
  OPEN_GL_OR_SKIP(context);
  const Character& c = default_humanoid();
  Shot shot;
  shot.copies = 160;  // the thesis scene
  shot.frame = 1;
  shot.mode = "compute";
  Frame compute = render(*context, c, shot);
  EXPECT_EQ(compute.counters.copies_visible, 124u);  // 36 of 160 culled (modes.md)
  EXPECT_EQ(compute.counters.draw_calls, compute.counters.copies_visible);
  EXPECT_EQ(compute.counters.bytes_uploaded, compute.counters.copies_visible * (c.skeleton.joint_count() * 48 + 64));
  EXPECT_EQ(compute.counters.vertices_skinned, 0u);
  EXPECT_EQ(compute.counters.poses_updated, compute.counters.copies_visible);
  shot.mode = "baked";
  Frame baked = render(*context, c, shot);
  EXPECT_EQ(baked.counters.copies_visible, 124u);
  EXPECT_EQ(baked.counters.draw_calls, 1u);  // one character, one material: one instanced draw
  // Instanced's record a copy (model, colour, samples, position): no palette.
  EXPECT_EQ(baked.counters.bytes_uploaded, baked.counters.copies_visible * sizeof(GpuInstance));
  EXPECT_EQ(baked.counters.poses_updated, 0u);  // no pose is built on the CPU
  EXPECT_EQ(baked.counters.vertices_skinned, 0u);
}

TEST(GpuSkinning, BakedAndComputeMemoryOnTheGpuIsWhatTheyHold) {
  OPEN_GL_OR_SKIP(context);
  const Character& c = default_humanoid();
  RendererConfig rc;
  rc.width = kWidth;
  rc.height = kHeight;
  GlCrowdRenderer renderer(*context, c, 160, rc);
  BenchConfig config;
  config.crowd.copies = 160;
  config.renderer = &renderer;
  config.mode = find_mode("baked")->switches;
  uint64_t samples = 0;
  for (const Action& a : c.actions) samples += baked_samples(a, config.bake_rate_hz);
  {
    CrowdBench bench(c, config);
    EXPECT_EQ(bench.bake_summary().samples, samples);
    // The table (48 bytes a joint a sample), room for a record a copy (16
    // bytes) and every copy's placement (48).
    EXPECT_EQ(bench.animation_gpu_bytes(),
              samples * c.skeleton.joint_count() * 48 + 160 * (sizeof(GpuInstance) + sizeof(GpuPlacement)));
    EXPECT_EQ(bench.step().counters.gpu_palette_bytes, bench.animation_gpu_bytes());
    EXPECT_GT(bench.bake_summary().bake_ms, 0.0);
  }
  config.mode = find_mode("compute")->switches;
  CrowdBench bench(c, config);
  // The rest mesh (64 bytes a vertex); a batch of all 160 copies' palettes and skinned vertices.
  uint64_t v = c.mesh.vertex_count(), j = c.skeleton.joint_count();
  EXPECT_EQ(bench.animation_gpu_bytes(), v * 64 + 160 * (j * 48 + v * 32));
  EXPECT_EQ(bench.step().counters.gpu_palette_bytes, bench.animation_gpu_bytes());
}

TEST(GpuSkinning, A300BoneCharacterRunsInComputeAndBakedWithoutFallback) {
  OPEN_GL_OR_SKIP(context);
  ASSERT_EQ(bony().skeleton.joint_count(), 300u);
  for (const char* mode : {"compute", "baked"}) {
    Shot shot;
    shot.mode = mode;
    Frame f = render(*context, bony(), shot);
    EXPECT_TRUE(f.gpu_skinned) << mode;
    EXPECT_EQ(f.counters.copies_fallback, 0u) << mode;
    EXPECT_EQ(f.counters.vertices_skinned, 0u) << mode;
  }
  Shot shot;
  shot.mode = "hwskin";  // the thesis's uniform array: 128 bones at most
  Frame f = render(*context, bony(), shot);
  EXPECT_FALSE(f.gpu_skinned);
  EXPECT_EQ(f.counters.copies_fallback, f.counters.poses_updated);
}

TEST(GpuSkinning, AContextWithoutComputeOrVertexStorageBuffersRefusesNamingIt) {
  OPEN_GL_OR_SKIP(context);
  for (auto [mode, hide, needle] : {std::tuple{"compute", "compute", "compute shaders"},
                                    std::tuple{"baked", "vertex-ssbo", "in the vertex shader"}}) {
    Shot shot;
    shot.mode = mode;
    shot.copies = 2;
    shot.hide_features = hide;
    try {
      render(*context, default_humanoid(), shot);
      FAIL() << mode << " ran on a context without what it needs";
    } catch (const GlUnavailable& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
    }
    shot.hide_features = mode == std::string("compute") ? "vertex-ssbo" : "compute";  // what it does not need
    EXPECT_GT(covered(render(*context, default_humanoid(), shot).rgba), 0u) << mode;
  }
  GlFeatures none;
  EXPECT_NE(missing_gl_feature(SkinningSite::Compute, none), "");
  EXPECT_NE(missing_gl_feature(SkinningSite::Baked, none), "");
  EXPECT_EQ(missing_gl_feature(SkinningSite::Gpu, none), "");  // hwskin's own check is require()'s
  GlFeatures enough;
  enough.compute_storage_blocks = enough.vertex_storage_blocks = 3;
  enough.max_storage_block_bytes = 1 << 27;
  EXPECT_EQ(missing_gl_feature(SkinningSite::Compute, enough), "");
  EXPECT_EQ(missing_gl_feature(SkinningSite::Baked, enough), "");
}

TEST(GpuSkinning, BakedDrawsOnceACharacterWhateverTheCrowd) {
  OPEN_GL_OR_SKIP(context);
  const Character* both[] = {&default_humanoid(), &bony()};
  Shot shot;
  shot.mode = "baked";
  shot.camera = "all";
  shot.frame = 2;
  for (size_t copies : {size_t{4}, size_t{40}}) {
    shot.copies = copies;
    Frame f = render(*context, both, shot);
    EXPECT_EQ(f.counters.copies_visible, copies);
    EXPECT_EQ(f.counters.draw_calls, 2u) << copies << " copies of two characters";
    EXPECT_EQ(f.counters.bytes_uploaded, sizeof(GpuInstance) * copies);
  }
}

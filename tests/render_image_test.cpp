// Rendered frames: software and hardware skinning draw the same crowd, a known
// pose covers the pixels it must and no others, EGL and OSMesa agree, and the
// counters say what was sent. Small frames (320x180) and few copies, so that
// llvmpipe draws them in milliseconds; skips when no GL backend opens.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "asset/errors.h"
#include "asset/gltf_loader.h"
#include "frame/crowd_bench.h"
#include "gen/humanoid.h"
#include "render/crowd_renderer.h"
#include "render/gl.h"
#include "render/gl_context.h"
#include "render/gl_errors.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

constexpr int kWidth = 320, kHeight = 180;

std::unique_ptr<GlContext> try_context(GlBackend backend, std::string* why) {
  try {
    return create_context(backend);
  } catch (const GlUnavailable& e) {
    *why = e.what();
    return nullptr;
  }
}

#define OPEN_GL_OR_SKIP(context)                                          \
  std::string why_##context;                                              \
  auto context = try_context(GlBackend::Egl, &why_##context);             \
  if (!context) context = try_context(GlBackend::OsMesa, &why_##context); \
  if (!context) GTEST_SKIP() << "no GL backend on this machine: " << why_##context

const Character& humanoid() {
  static const Character character = load_character((test::source_dir() / "scenes" / "humanoid.glb").string());
  return character;
}

struct Frame {
  std::vector<uint8_t> rgba;
  Counters counters;
  bool gpu_skinned = false;
  std::vector<glm::vec2> pixels_of_vertices;  // copy 0's skinned vertices on screen, when CPU-skinned
};

struct Shot {
  std::string mode = "threaded";
  size_t copies = 8;
  size_t frame = 7;
  std::string camera = "default";
  size_t joint_cap = 128;
  bool random_actions = false;
  float bake_rate = kDefaultBakeRateHz;
};

// Runs frames 0..shot.frame of a bench with a renderer and reads the last back.
Frame render(GlContext& context, const Character& character, const Shot& shot) {
  context.make_current();
  RendererConfig rc;
  rc.width = kWidth;
  rc.height = kHeight;
  rc.joint_cap = shot.joint_cap;
  GlCrowdRenderer renderer(context, character, shot.copies, rc);
  BenchConfig config;
  config.mode = find_mode(shot.mode)->switches;
  config.mode_name = shot.mode;
  config.threads = 2;
  config.crowd.copies = shot.copies;
  config.camera = shot.camera;
  config.aspect = static_cast<float>(kWidth) / kHeight;
  config.renderer = &renderer;
  if (shot.random_actions) config.crowd.actions = ActionChoice::Random;
  config.bake_rate_hz = shot.bake_rate;
  CrowdBench bench(character, config);
  Frame frame;
  for (size_t k = 0; k <= shot.frame; ++k) frame.counters = bench.step().counters;
  frame.rgba = renderer.read_pixels();
  frame.gpu_skinned = bench.gpu_skinned();
  if (!frame.gpu_skinned) {
    glm::mat4 to_clip = bench.camera().view_projection() * bench.crowd().world[0];
    for (const glm::vec3& p : bench.skinned_positions(0)) {
      glm::vec4 clip = to_clip * glm::vec4(p, 1.0f);
      glm::vec2 ndc = glm::vec2(clip) / clip.w;
      // Pixel coordinates, rows from the top as read_pixels gives them.
      frame.pixels_of_vertices.emplace_back((ndc.x * 0.5f + 0.5f) * kWidth, (0.5f - ndc.y * 0.5f) * kHeight);
    }
  }
  return frame;
}

bool is_background(const std::vector<uint8_t>& rgba, size_t pixel) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(rgba[4 * pixel + c] - static_cast<int>(std::lround(kBackground[c] * 255.0f))) > 1) return false;
  return true;
}

size_t covered(const std::vector<uint8_t>& rgba) {
  size_t count = 0;
  for (size_t p = 0; p < rgba.size() / 4; ++p) count += !is_background(rgba, p);
  return count;
}

// Pixels whose largest channel difference exceeds `tolerance`.
size_t pixels_differing(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int tolerance) {
  size_t count = 0;
  for (size_t p = 0; p < a.size() / 4; ++p) {
    int worst = 0;
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(a[4 * p + c] - b[4 * p + c]));
    count += worst > tolerance;
  }
  return count;
}

// How far (in pixels) point p lies inside triangle abc, along the nearest edge's
// normal: negative outside. Zero for a degenerate triangle.
float inside_by(glm::vec2 a, glm::vec2 b, glm::vec2 c, glm::vec2 p) {
  float twice_area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  if (twice_area == 0.0f) return -1e9f;
  float sign = twice_area > 0 ? 1.0f : -1.0f, nearest = 1e9f;
  const glm::vec2 corners[3] = {a, b, c};
  for (int e = 0; e < 3; ++e) {
    glm::vec2 u = corners[e], v = corners[(e + 1) % 3];
    float cross = (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x);
    nearest = std::min(nearest, sign * cross / glm::distance(u, v));
  }
  return nearest;
}

// The known pose, with copy 0's CPU-skinned vertices projected as the camera
// does: every pixel whose centre lies inside a front-facing triangle (by a
// margin for rounding) must be drawn; every pixel more than a pixel away from
// all triangles must be empty (copy 0 is the only copy).
void expect_pose_coverage(const Character& character, const Frame& expected, const Frame& image,
                          const std::string& what) {
  const std::vector<glm::vec2>& v = expected.pixels_of_vertices;
  ASSERT_FALSE(v.empty());
  std::vector<uint8_t> must(kWidth * kHeight, 0), may(kWidth * kHeight, 0);
  const std::vector<uint32_t>& indices = character.mesh.indices;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    glm::vec2 a = v[indices[t]], b = v[indices[t + 1]], c = v[indices[t + 2]];
    // Rows run down the screen, so GL's counter-clockwise front faces turn clockwise here.
    bool front = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y) < 0;
    glm::vec2 low = glm::max(glm::floor(glm::min(a, glm::min(b, c))) - 2.0f, glm::vec2(0));
    glm::vec2 high = glm::min(glm::ceil(glm::max(a, glm::max(b, c))) + 2.0f, glm::vec2(kWidth - 1, kHeight - 1));
    for (int y = static_cast<int>(low.y); y <= static_cast<int>(high.y); ++y)
      for (int x = static_cast<int>(low.x); x <= static_cast<int>(high.x); ++x) {
        float inside = inside_by(a, b, c, glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f));
        size_t pixel = static_cast<size_t>(y) * kWidth + static_cast<size_t>(x);
        if (front && inside >= 0.05f) must[pixel] = 1;
        if (inside >= -1.0f) may[pixel] = 1;
      }
  }
  size_t required = 0, missed = 0, stray = 0, drawn = 0;
  for (size_t p = 0; p < must.size(); ++p) {
    bool empty = is_background(image.rgba, p);
    required += must[p];
    missed += must[p] && empty;
    stray += !may[p] && !empty;
    drawn += !empty;
  }
  std::cout << "[ info ] " << what << ": " << required << " pixels must be drawn, " << drawn << " are\n";
  EXPECT_GT(required, must.size() / 100) << what << ": the character is too small in the frame to check";
  EXPECT_EQ(missed, 0u) << what << ": pixels inside its triangles left empty";
  EXPECT_EQ(stray, 0u) << what << ": pixels drawn away from all its triangles";
}

}  // namespace

TEST(RenderImage, SoftwareAndHardwareSkinningDrawTheSameFrame) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  Frame software = render(*context, humanoid(), shot);
  shot.mode = "hwskin";
  Frame hardware = render(*context, humanoid(), shot);
  ASSERT_FALSE(software.gpu_skinned);
  ASSERT_TRUE(hardware.gpu_skinned);
  size_t pixels = software.rgba.size() / 4;
  ASSERT_GT(covered(software.rgba), pixels / 50);
  std::cout << "[ info ] of " << covered(software.rgba) << " pixels drawn, " << pixels_differing(software.rgba, hardware.rgba, 0)
            << " differ, " << pixels_differing(software.rgba, hardware.rgba, 4) << " by more than 4\n";
  // The two sum the same matrices in different orders: edges may move by a
  // pixel, shading by a shade.
  size_t drawn = covered(software.rgba);
  EXPECT_LE(pixels_differing(software.rgba, hardware.rgba, 4), drawn / 100);
  EXPECT_LE(pixels_differing(software.rgba, hardware.rgba, 64), drawn / 500);
  double a = static_cast<double>(covered(software.rgba)), b = static_cast<double>(covered(hardware.rgba));
  EXPECT_NEAR(a, b, 0.005 * a);
}

TEST(RenderImage, AKnownPoseCoversWhatItMustAndNothingElse) {
  OPEN_GL_OR_SKIP(context);
  std::vector<std::pair<std::string, std::string>> characters = {
      {"humanoid", (test::source_dir() / "scenes" / "humanoid.glb").string()}};
  if (test::have_samples()) {
    characters.emplace_back("CesiumMan", test::sample("CesiumMan/glTF-Binary/CesiumMan.glb"));
    characters.emplace_back("Fox", test::sample("Fox/glTF-Binary/Fox.glb"));
  } else {
    std::cout << "[ info ] sample characters not found: checking the generated humanoid only\n";
  }
  for (const auto& [name, file] : characters) {
    Character character = load_character(file);
    Shot shot;
    shot.copies = 1;
    shot.frame = 12;
    shot.camera = "all";  // for one copy: the copy, filling most of the frame
    Frame software = render(*context, character, shot);
    expect_pose_coverage(character, software, software, name + " skinned on the CPU");
    shot.mode = "hwskin";
    Frame hardware = render(*context, character, shot);
    ASSERT_TRUE(hardware.gpu_skinned) << name;
    expect_pose_coverage(character, software, hardware, name + " skinned on the GPU");
  }
}

TEST(RenderImage, EglAndOsMesaDrawTheSameImage) {
  std::string why;
  auto egl = try_context(GlBackend::Egl, &why);
  if (!egl) GTEST_SKIP() << why;
  auto osmesa = try_context(GlBackend::OsMesa, &why);
  if (!osmesa) GTEST_SKIP() << why;
  for (const char* mode : {"threaded", "hwskin"}) {
    Shot shot;
    shot.mode = mode;
    shot.camera = "default";
    shot.copies = 8;
    // Alternating contexts also checks that glad follows the current one.
    Frame a = render(*egl, humanoid(), shot);
    Frame b = render(*osmesa, humanoid(), shot);
    ASSERT_GT(covered(a.rgba), a.rgba.size() / 4 / 100) << mode;
    if (egl->renderer() == osmesa->renderer())
      EXPECT_EQ(pixels_differing(a.rgba, b.rgba, 0), 0u) << mode << " on " << egl->renderer();
    else  // a GPU against llvmpipe: rasterisation rules differ at edges
      EXPECT_LT(pixels_differing(a.rgba, b.rgba, 8), a.rgba.size() / 4 / 100) << mode;
  }
}

TEST(RenderImage, CountersSayWhatWasSent) {
  OPEN_GL_OR_SKIP(context);
  const Character& c = humanoid();
  uint64_t vertex_bytes = c.mesh.vertex_count() * 24 + 64, bone_bytes = c.skeleton.joint_count() * 48 + 64;
  Shot shot;
  shot.camera = "default";
  shot.copies = 8;
  shot.frame = 1;
  for (const char* mode : {"master", "culled", "threaded", "hwskin"}) {
    shot.mode = mode;
    Frame f = render(*context, c, shot);
    EXPECT_GT(f.counters.copies_visible, 0u) << mode;
    EXPECT_EQ(f.counters.draw_calls, f.counters.copies_visible) << mode;
    uint64_t per_copy = f.gpu_skinned ? bone_bytes : vertex_bytes;
    EXPECT_EQ(f.counters.bytes_uploaded, f.counters.copies_visible * per_copy) << mode;
    EXPECT_EQ(f.counters.copies_fallback, 0u) << mode;
  }
  // The thesis's character: 4,951 vertices against 69 bones.
  EXPECT_EQ(vertex_bytes, 118'888u);
  EXPECT_EQ(bone_bytes, 3'376u);
}

TEST(RenderImage, ACharacterOverTheBoneLimitFallsBackToTheCpu) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  Frame reference = render(*context, humanoid(), shot);
  shot.mode = "hwskin";
  shot.joint_cap = 8;  // the humanoid has 69 joints
  Frame fallback = render(*context, humanoid(), shot);
  EXPECT_FALSE(fallback.gpu_skinned);
  EXPECT_GT(fallback.counters.copies_fallback, 0u);
  EXPECT_EQ(fallback.counters.copies_fallback, fallback.counters.poses_updated);
  EXPECT_EQ(fallback.counters.vertices_skinned, fallback.counters.poses_updated * humanoid().mesh.vertex_count());
  EXPECT_EQ(fallback.counters.bytes_uploaded, fallback.counters.draw_calls * (humanoid().mesh.vertex_count() * 24 + 64));
  // Skinned by the same code as threaded: the same image, bit for bit.
  EXPECT_EQ(pixels_differing(reference.rgba, fallback.rgba, 0), 0u);
}

TEST(RenderImage, AGlErrorDuringAFrameStopsItNamingTheStage) {
  OPEN_GL_OR_SKIP(context);
  RendererConfig rc;
  rc.width = kWidth;
  rc.height = kHeight;
  GlCrowdRenderer renderer(*context, humanoid(), 2, rc);
  BenchConfig config;
  config.mode = find_mode("hwskin")->switches;
  config.crowd.copies = 2;
  config.renderer = &renderer;
  CrowdBench bench(humanoid(), config);
  bench.step();
  glBindBuffer(GL_ARRAY_BUFFER, 987654);  // an error, as a driver bug would leave one
  try {
    bench.step();
    FAIL() << "the frame went on";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("GL_INVALID_OPERATION during Rasterizer"), std::string::npos) << e.what();
  }
}

TEST(RenderImage, HardwareSkinningNeedsARenderer) {
  BenchConfig config;
  config.mode = find_mode("hwskin")->switches;
  config.crowd.copies = 2;
  try {
    CrowdBench bench(humanoid(), config);
    FAIL() << "hwskin ran without a renderer";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--backend"), std::string::npos) << e.what();
  }
}

// Issue 12: modes compute and baked.

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
  std::vector<Subject> list = {{"humanoid", &humanoid()}, {"300 bones", &bony()}, {"random actions", &humanoid(), true}};
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
TEST(RenderImage, ComputeAndBakedDrawWhatCpuSkinningDraws) {
  OPEN_GL_OR_SKIP(context);
  std::vector<Character> loaded;
  for (const Subject& subject : subjects(loaded)) {
    Shot shot;
    shot.random_actions = subject.random_actions;
    shot.copies = subject.random_actions ? 24 : 8;
    Frame software = render(*context, *subject.character, shot);
    size_t pixels = software.rgba.size() / 4, drawn = covered(software.rgba);
    ASSERT_GT(drawn, pixels / 200) << subject.name;
    for (const char* mode : {"compute", "baked"}) {
      shot.mode = mode;
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

TEST(RenderImage, ComputeAndBakedCountWhatTheySend) {
  OPEN_GL_OR_SKIP(context);
  const Character& c = humanoid();
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
  EXPECT_EQ(baked.counters.bytes_uploaded, baked.counters.copies_visible * 16);  // <= 32 a copy
  EXPECT_EQ(baked.counters.poses_updated, 0u);  // no pose is built on the CPU
  EXPECT_EQ(baked.counters.vertices_skinned, 0u);
}

TEST(RenderImage, BakedAndComputeMemoryOnTheGpuIsWhatTheyHold) {
  OPEN_GL_OR_SKIP(context);
  const Character& c = humanoid();
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
    // The table (48 bytes a joint a sample), placements (80 a copy), instances (16 a copy).
    EXPECT_EQ(bench.animation_gpu_bytes(), samples * c.skeleton.joint_count() * 48 + 160 * 80 + 160 * 16);
    EXPECT_GT(bench.bake_summary().bake_ms, 0.0);
  }
  config.mode = find_mode("compute")->switches;
  CrowdBench bench(c, config);
  // The rest mesh (64 bytes a vertex); a batch of all 160 copies' palettes and skinned vertices.
  uint64_t v = c.mesh.vertex_count(), j = c.skeleton.joint_count();
  EXPECT_EQ(bench.animation_gpu_bytes(), v * 64 + 160 * (j * 48 + v * 32));
}

TEST(RenderImage, A300BoneCharacterRunsInComputeAndBakedWithoutFallback) {
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

TEST(RenderImage, AContextWithoutComputeOrVertexStorageBuffersRefusesNamingIt) {
  OPEN_GL_OR_SKIP(context);
  for (auto [mode, needle] : {std::pair{"compute", "compute shaders"}, std::pair{"baked", "vertex shader"}}) {
    RendererConfig rc;
    rc.width = kWidth;
    rc.height = kHeight;
    rc.pretend_limits = GlFeatureLimits{};  // none of either
    GlCrowdRenderer renderer(*context, humanoid(), 2, rc);
    BenchConfig config;
    config.mode = find_mode(mode)->switches;
    config.crowd.copies = 2;
    config.renderer = &renderer;
    try {
      CrowdBench bench(humanoid(), config);
      FAIL() << mode << " ran on a context without what it needs";
    } catch (const GlUnavailable& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
    }
  }
  EXPECT_EQ(missing_gl_feature(SkinningSite::Compute, {3, 0}), "");
  EXPECT_EQ(missing_gl_feature(SkinningSite::Baked, {0, 3}), "");
  EXPECT_EQ(missing_gl_feature(SkinningSite::Gpu, {}), "");  // hwskin uses uniforms
}

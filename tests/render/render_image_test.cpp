// Rendered frames: software and hardware skinning draw the same crowd, a known
// pose covers the pixels it must and no others, EGL and OSMesa agree, and the
// counters say what was sent. Small frames (320x180) and few copies, so that
// llvmpipe draws them in milliseconds; skips when no GL backend opens.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "frame/crowd_bench.h"
#include "render/crowd_renderer.h"
#include "render/gl.h"
#include "render/gl_context.h"
#include "render/gl_errors.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

using namespace crowdprof::test;

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
  Frame software = render(*context, default_humanoid(), shot);
  shot.mode = "hwskin";
  Frame hardware = render(*context, default_humanoid(), shot);
  ASSERT_FALSE(software.gpu_skinned);
  ASSERT_TRUE(hardware.gpu_skinned);
  size_t pixels = software.rgba.size() / 4;
  ASSERT_GT(covered(software.rgba), pixels / 50);
  std::cout << "[ info ] of " << covered(software.rgba) << " pixels drawn, "
            << pixels_differing(software.rgba, hardware.rgba, 0) << " differ, "
            << pixels_differing(software.rgba, hardware.rgba, 4) << " by more than 4\n";
  // The two sum the same matrices in different orders: edges may move by a
  // pixel, shading by a shade.
  size_t drawn = covered(software.rgba);
  EXPECT_LE(pixels_differing(software.rgba, hardware.rgba, 4), drawn / 100);
  EXPECT_LE(pixels_differing(software.rgba, hardware.rgba, 64), drawn / 500);
  double a = static_cast<double>(covered(software.rgba)), b = static_cast<double>(covered(hardware.rgba));
  EXPECT_NEAR(a, b, 0.005 * a);
}

// --vertex-format packed: the same frame from 16-bit positions and 10:10:10:2
// normals, decoded by the vertex shader: shading may move by a level or two
// where a normal rounds, but no more than 0.05% of the pixels differ by more
// than 4 levels (an edge that moved); and the
// counters say 10 bytes a vertex were sent instead of 24.
TEST(RenderImage, PackedVerticesDrawTheFloatFrame) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  Frame floats = render(*context, default_humanoid(), shot);
  shot.vertex_format = VertexFormat::Packed;
  Frame packed = render(*context, default_humanoid(), shot);
  size_t pixels = floats.rgba.size() / 4;
  ASSERT_GT(covered(floats.rgba), pixels / 50);
  std::cout << "[ info ] of " << covered(floats.rgba) << " pixels drawn, "
            << pixels_differing(floats.rgba, packed.rgba, 0) << " differ, "
            << pixels_differing(floats.rgba, packed.rgba, 4) << " by more than 4\n";
  EXPECT_LE(pixels_differing(floats.rgba, packed.rgba, 4), pixels * 5 / 10000);
  EXPECT_LE(pixels_differing(floats.rgba, packed.rgba, 0), covered(floats.rgba) / 10);
  EXPECT_EQ(floats.counters.draw_calls, packed.counters.draw_calls);
  const uint64_t copies = floats.counters.draw_calls, vertices = default_humanoid().mesh.vertex_count();
  EXPECT_EQ(copies * (vertices * 24 + 64), floats.counters.bytes_uploaded);
  EXPECT_EQ(copies * (vertices * 10 + 64), packed.counters.bytes_uploaded);
  // A pose the float path draws differently would move many pixels: the
  // packed frame is of the same pose, not the rest pose.
  shot.frame = 0;
  Frame earlier = render(*context, default_humanoid(), shot);
  EXPECT_GT(pixels_differing(earlier.rgba, packed.rgba, 4), pixels * 5 / 10000);
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
    Frame a = render(*egl, default_humanoid(), shot);
    Frame b = render(*osmesa, default_humanoid(), shot);
    ASSERT_GT(covered(a.rgba), a.rgba.size() / 4 / 100) << mode;
    if (egl->renderer() == osmesa->renderer())
      EXPECT_EQ(pixels_differing(a.rgba, b.rgba, 0), 0u) << mode << " on " << egl->renderer();
    else  // a GPU against llvmpipe: rasterisation rules differ at edges
      EXPECT_LT(pixels_differing(a.rgba, b.rgba, 8), a.rgba.size() / 4 / 100) << mode;
  }
}

TEST(RenderImage, CountersSayWhatWasSent) {
  OPEN_GL_OR_SKIP(context);
  const Character& c = default_humanoid();
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
  Frame reference = render(*context, default_humanoid(), shot);
  shot.mode = "hwskin";
  shot.joint_cap = 8;  // the humanoid has 69 joints
  Frame fallback = render(*context, default_humanoid(), shot);
  EXPECT_FALSE(fallback.gpu_skinned);
  EXPECT_GT(fallback.counters.copies_fallback, 0u);
  EXPECT_EQ(fallback.counters.copies_fallback, fallback.counters.poses_updated);
  EXPECT_EQ(fallback.counters.vertices_skinned,
            fallback.counters.poses_updated * default_humanoid().mesh.vertex_count());
  EXPECT_EQ(fallback.counters.bytes_uploaded,
            fallback.counters.draw_calls * (default_humanoid().mesh.vertex_count() * 24 + 64));
  // Skinned by the same code as threaded: the same image, bit for bit.
  EXPECT_EQ(pixels_differing(reference.rgba, fallback.rgba, 0), 0u);
}

TEST(RenderImage, AGlErrorDuringAFrameStopsItNamingTheStage) {
  OPEN_GL_OR_SKIP(context);
  RendererConfig rc;
  rc.width = kWidth;
  rc.height = kHeight;
  GlCrowdRenderer renderer(*context, default_humanoid(), 2, rc);
  BenchConfig config;
  config.mode = find_mode("hwskin")->switches;
  config.crowd.copies = 2;
  config.renderer = &renderer;
  CrowdBench bench(default_humanoid(), config);
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
    CrowdBench bench(default_humanoid(), config);
    FAIL() << "hwskin ran without a renderer";
  } catch (const SettingsUsageError& e) {
    EXPECT_NE(e.marked().find("needs a GL backend: {backend} auto"), std::string::npos) << e.marked();
  }
}

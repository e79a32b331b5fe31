// The image-test machinery shared by the rendering tests: a GL context or a
// skip, a crowd drawn for a few frames and read back, and pixel comparisons.
// Small frames (320x180) and few copies, so that llvmpipe draws them in
// milliseconds.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "asset/character.h"
#include "asset/gltf_loader.h"
#include "frame/crowd_bench.h"
#include "gen/humanoid.h"
#include "render/crowd_renderer.h"
#include "render/gl_context.h"
#include "render/gl_errors.h"
#include "test_support.h"

namespace crowdprof::test {

inline constexpr int kWidth = 320, kHeight = 180;

inline std::unique_ptr<GlContext> try_context(GlBackend backend, std::string* why) {
  try {
    return create_context(backend);
  } catch (const GlUnavailable& e) {
    *why = e.what();
    return nullptr;
  }
}

}  // namespace crowdprof::test

#define OPEN_GL_OR_SKIP(context)                                                                      \
  std::string why_##context;                                                                          \
  auto context = crowdprof::test::try_context(crowdprof::GlBackend::Egl, &why_##context);             \
  if (!context) context = crowdprof::test::try_context(crowdprof::GlBackend::OsMesa, &why_##context); \
  if (!context) GTEST_SKIP() << "no GL backend on this machine: " << why_##context

namespace crowdprof::test {

struct Frame {
  std::vector<uint8_t> rgba;
  Counters counters;
  bool gpu_skinned = false;
  std::string digest;
  std::vector<glm::vec2> pixels_of_vertices;  // copy 0's skinned vertices on screen, when CPU-skinned
  std::vector<GpuTime> gpu_times;             // every frame's that was read back
};

struct Shot {
  std::string mode = "threaded";
  size_t copies = 8;
  size_t frame = 7;
  std::string camera = "default";
  size_t joint_cap = 128;
  ActionChoice actions = ActionChoice::Shared;
  std::string hide_features;             // gl_features.h
  float bake_rate = kDefaultBakeRateHz;  // skinning baked
  VertexFormat vertex_format = VertexFormat::Float;
  uint32_t passes = 1;  // modes.h
  FrustumTest frustum = FrustumTest::Cpu;
  bool mesh_lod = false;
  MeshLodThresholds mesh_lod_at;
  IndexOrder index_order = IndexOrder::Optimized;
  double transitions_s = 0.0;  // > 0: copies change action and fade (issue 53)
  double blend_in_s = 0.25;
  Crossfade crossfade = Crossfade::Sampled;
};

// Runs frames 0..shot.frame of a bench of `characters` (one group each, their
// copies split evenly) with a renderer and reads the last back.
inline Frame render(GlContext& context, std::span<const Character* const> characters, const Shot& shot) {
  context.make_current();
  RendererConfig rc;
  rc.width = kWidth;
  rc.height = kHeight;
  rc.joint_cap = shot.joint_cap;
  rc.hide_features = shot.hide_features;
  GlCrowdRenderer renderer(context, characters, shot.copies, rc);
  BenchConfig config;
  config.mode = find_mode(shot.mode)->switches;
  config.mode.vertex_format = shot.vertex_format;
  config.mode.passes = shot.passes;
  config.mode.frustum = shot.frustum;
  config.mode.mesh_lod = shot.mesh_lod;
  config.mode.mesh_lod_at = shot.mesh_lod_at;
  config.mode.index_order = shot.index_order;
  config.mode.transitions_s = shot.transitions_s;
  if (shot.transitions_s > 0) config.mode.blend_in_s = shot.blend_in_s, config.mode.crossfade = shot.crossfade;
  config.mode_name = shot.mode;
  config.threads = 2;
  config.crowd.copies = shot.copies;
  config.crowd.actions = shot.actions;
  if (characters.size() > 1)
    for (size_t k = 0; k < characters.size(); ++k) {
      CrowdGroup group;
      group.character = k;
      group.copies = shot.copies / characters.size() + (k < shot.copies % characters.size());
      group.actions = shot.actions;
      config.crowd.groups.push_back(group);
    }
  config.camera = shot.camera;
  config.aspect = static_cast<float>(kWidth) / kHeight;
  config.renderer = &renderer;
  config.bake_rate_hz = shot.bake_rate;
  CrowdBench bench(characters, config);
  Frame frame;
  for (size_t k = 0; k <= shot.frame; ++k) frame.counters = bench.step().counters;
  frame.rgba = renderer.read_pixels();
  frame.gpu_skinned = bench.gpu_skinned();
  frame.digest = bench.digest();
  bench.collect_gpu_times();
  frame.gpu_times.assign(bench.gpu_times().begin(), bench.gpu_times().end());
  if (!bench.gpu_skinned_copy(0) && !bench.packed_vertices()) {
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

inline Frame render(GlContext& context, const Character& character, const Shot& shot) {
  const Character* one[] = {&character};
  return render(context, one, shot);
}

// A second, smaller character (30 bones, 800 vertices): in a crowd beside the
// humanoid, each has its own range of records, its own draws and palettes of
// another size.
inline const Character& thirty_bone_humanoid() {
  static const Character character = [] {
    HumanoidOptions options;
    options.bones = 30;
    options.vertices = 800;
    return generate_humanoid(options);
  }();
  return character;
}

// scenes/humanoid.glb, the thesis's character, loaded once.
inline const Character& default_humanoid() {
  static const Character character = load_character((source_dir() / "scenes" / "humanoid.glb").string());
  return character;
}

inline bool is_background(const std::vector<uint8_t>& rgba, size_t pixel) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(rgba[4 * pixel + c] - static_cast<int>(std::lround(kBackground[c] * 255.0f))) > 1) return false;
  return true;
}

inline size_t covered(const std::vector<uint8_t>& rgba) {
  size_t count = 0;
  for (size_t p = 0; p < rgba.size() / 4; ++p) count += !is_background(rgba, p);
  return count;
}

// Pixels whose largest channel difference exceeds `tolerance`.
inline size_t pixels_differing(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int tolerance) {
  size_t count = 0;
  for (size_t p = 0; p < a.size() / 4; ++p) {
    int worst = 0;
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(a[4 * p + c] - b[4 * p + c]));
    count += worst > tolerance;
  }
  return count;
}

}  // namespace crowdprof::test

// Transitions on the GPU (issue 53 item 3): the GPU palette modes draw the
// blended palettes the CPU built; baked mixes two baked records in its vertex
// shader, a fading copy sending 32 bytes; the drawn-error audit measures
// baked fading copies against their exact blend.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "animation/bake.h"
#include "animation/binding.h"
#include "render/gpu_frame_buffers.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;
using namespace crowdprof::test;

namespace {

// Random actions, a change a second on average, 0.4 s fades: at frame 40 a
// good part of the crowd is mid-fade.
Shot fading_shot(const char* mode, size_t copies = 24) {
  Shot shot;
  shot.mode = mode;
  shot.copies = copies;
  shot.frame = 40;
  shot.actions = ActionChoice::Random;
  shot.transitions_s = 1.0;
  shot.blend_in_s = 0.4;
  return shot;
}

BenchConfig fading_config(const char* mode, GlCrowdRenderer* renderer, size_t copies = 24,
                          Crossfade crossfade = Crossfade::Sampled) {
  const Shot shot = fading_shot(mode, copies);
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode.transitions_s = shot.transitions_s;
  config.mode.blend_in_s = shot.blend_in_s;
  config.mode.crossfade = crossfade;
  config.mode_name = mode;
  config.threads = 2;
  config.crowd.copies = copies;
  config.crowd.actions = shot.actions;
  config.aspect = static_cast<float>(kWidth) / kHeight;
  config.renderer = renderer;
  return config;
}

RendererConfig small_fading_frame() {
  RendererConfig rc;
  rc.width = kWidth;
  rc.height = kHeight;
  return rc;
}

// Each vertex of `mesh` skinned by `palette` (positions only).
std::vector<glm::vec3> skin_positions(const SkinnedMesh& mesh, std::span<const SkinMatrix> palette) {
  std::vector<glm::vec3> out(mesh.vertex_count());
  for (size_t v = 0; v < out.size(); ++v) {
    glm::vec4 p(0.0f);
    for (int k = 0; k < 4; ++k)
      p += mesh.weights[v][k] * (palette[mesh.joints[v][k]] * glm::vec4(mesh.positions[v], 1));
    out[v] = glm::vec3(p);
  }
  return out;
}

double largest_distance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  double most = 0;
  for (size_t v = 0; v < a.size(); ++v) most = std::max(most, static_cast<double>(glm::distance(a[v], b[v])));
  return most;
}

// The humanoid's actions baked as mode baked bakes them (the default rate).
const BakedCharacter& baked_humanoid() {
  static const BakedCharacter baked = [] {
    const Character& c = default_humanoid();
    std::vector<ActionBindings> bindings;
    for (const Action& action : c.actions) bindings.push_back(bind_action(c.skeleton, action));
    std::vector<std::span<const int32_t>> targets;
    for (const ActionBindings& b : bindings) targets.emplace_back(b.targets);
    BakedCharacter out;
    EXPECT_TRUE(bake_character(c, targets, kDefaultBakeRateHz, &out));
    return out;
  }();
  return baked;
}

std::span<const SkinMatrix> samples_of(const BakedCharacter& baked, uint32_t first_sample, uint32_t intervals) {
  return std::span(baked.matrices).subspan(size_t{first_sample} * baked.joints, (size_t{intervals} + 1) * baked.joints);
}

// What baked.vert draws for copy `copy` of `view`: its record, mixed with the
// action it leaves when it fades, unless `ignore_fade` (a shader that
// dropped the fade's weight).
std::vector<SkinMatrix> baked_drawn_palette(const FrameView& view, size_t copy, bool ignore_fade = false) {
  const BakedCharacter& baked = baked_humanoid();
  std::vector<SkinMatrix> palette(baked.joints), from(baked.joints);
  const BakedInstance& now = view.baked[copy];
  const BakedPaletteJob now_job{samples_of(baked, now.first_sample, now.intervals), baked.joints, now.position,
                                palette};
  const BakedFade& fade = view.baked_fades[copy];
  if (!fade.fading() || ignore_fade) {
    EXPECT_TRUE(now_job.Run());
    return palette;
  }
  const BakedPaletteJob from_job{samples_of(baked, fade.first_sample, fade.intervals), baked.joints, fade.position,
                                 from};
  EXPECT_TRUE((BakedFadeJob{now_job, from_job, fade.weight}.Run()));
  return palette;
}

size_t fading_on_screen(const FrameView& view) {
  size_t n = 0;
  for (size_t i = 0; i < view.copies(); ++i) n += view.visible[i] && view.baked_fades[i].fading();
  return n;
}

}  // namespace

// baked takes transitions; frustum gpu, whose cull pass times the copies from
// a clock fixed at load, refuses them naming what works.
TEST(TransitionsOnTheGpu, BakedTakesTransitionsButNotFrustumGpu) {
  ModeSwitches s = find_mode("baked")->switches;
  s.transitions_s = 1.0;
  EXPECT_EQ(conflicts(s).str(), "");
  s.frustum = FrustumTest::Gpu;
  EXPECT_NE(conflicts(s).marked().find("{frustum} cpu"), std::string::npos) << conflicts(s).str();
  s.transitions_s = 0.0;
  EXPECT_EQ(conflicts(s).str(), "");
}

// The GPU palette modes skin the palettes the CPU blended: their image is CPU
// skinning's within the exact modes' tolerance (gpu_modes_test.cpp), on a
// frame whose fades show (the same crowd snapping differs by more).
TEST(TransitionsOnTheGpu, PaletteModesDrawTheBlendedPoses) {
  OPEN_GL_OR_SKIP(context);
  const Character& humanoid = default_humanoid();
  Frame cpu = render(*context, humanoid, fading_shot("threaded"));
  ASSERT_GT(cpu.counters.fades, 3u) << "copies mid-fade in the frame compared";
  const size_t pixels = cpu.rgba.size() / 4;
  ASSERT_GT(covered(cpu.rgba), pixels / 200);
  Shot snap = fading_shot("threaded");
  snap.blend_in_s = 0.0;
  const Frame snapped = render(*context, humanoid, snap);
  EXPECT_GT(pixels_differing(cpu.rgba, snapped.rgba, 4) * 2000, pixels) << "the fades change the image";
  for (const char* mode : {"hwskin", "buffer", "instanced", "compute"}) {
    Frame gpu = render(*context, humanoid, fading_shot(mode));
    EXPECT_TRUE(gpu.gpu_skinned) << mode;
    EXPECT_EQ(gpu.counters.fades, cpu.counters.fades) << mode;
    const size_t differing = pixels_differing(cpu.rgba, gpu.rgba, 4);
    std::cout << "[ info ] " << mode << " with transitions: " << differing << " of " << covered(cpu.rgba)
              << " pixels drawn differ by more than 4 (snapping: " << pixels_differing(cpu.rgba, snapped.rgba, 4)
              << ")\n";
    EXPECT_LE(differing * 2000, pixels) << mode;
  }
}

// baked.vert mixes the two records as BakedFadeJob does: the image equals one
// drawn by hwskin from the palettes BakedFadeJob makes, within the exact
// modes' tolerance, and not one made with the fade's weight ignored.
TEST(TransitionsOnTheGpu, BakedMixesTwoRecordsAsBakedFadeJobDoes) {
  OPEN_GL_OR_SKIP(context);
  const Character& humanoid = default_humanoid();
  context->make_current();
  std::vector<uint8_t> baked_image;
  std::vector<std::vector<SkinMatrix>> mixed, unmixed;  // per copy: as drawn, and with the weight ignored
  size_t fading = 0;
  {
    GlCrowdRenderer renderer(*context, humanoid, 24, small_fading_frame());
    CrowdBench bench(humanoid, fading_config("baked", &renderer));
    for (size_t f = 0; f <= 40; ++f) bench.step();
    baked_image = renderer.read_pixels();
    fading = fading_on_screen(bench.view());
    for (size_t i = 0; i < bench.crowd().size(); ++i) {
      mixed.push_back(baked_drawn_palette(bench.view(), i));
      unmixed.push_back(baked_drawn_palette(bench.view(), i, true));
    }
  }
  ASSERT_GT(fading, 3u);
  auto drawn_by_hwskin = [&](const std::vector<std::vector<SkinMatrix>>& palettes) {
    GlCrowdRenderer renderer(*context, humanoid, 24, small_fading_frame());
    CrowdBench bench(humanoid, fading_config("hwskin", &renderer));
    for (size_t f = 0; f <= 40; ++f) bench.step();
    // The same view, each copy's palette replaced by the one given.
    FrameView view = bench.view();
    std::vector<SkinMatrix> all(view.palettes.begin(), view.palettes.end());
    for (size_t i = 0; i < view.copies(); ++i)
      std::copy(palettes[i].begin(), palettes[i].end(),
                all.begin() + static_cast<std::ptrdiff_t>(view.joint_offset[i]));
    view.palettes = all;
    Counters unused;
    renderer.draw(view, unused);
    renderer.finish();
    return renderer.read_pixels();
  };
  const std::vector<uint8_t> expected = drawn_by_hwskin(mixed), wrong = drawn_by_hwskin(unmixed);
  const size_t pixels = expected.size() / 4;
  ASSERT_GT(covered(expected), pixels / 200);
  const size_t differing = pixels_differing(expected, baked_image, 4);
  std::cout << "[ info ] baked with " << fading << " copies fading: " << differing << " of " << covered(expected)
            << " pixels differ by more than 4 from BakedFadeJob's palettes; the weight ignored: "
            << pixels_differing(wrong, baked_image, 4) << "\n";
  EXPECT_LE(differing * 2000, pixels);
  EXPECT_GT(pixels_differing(wrong, baked_image, 4) * 2000, pixels) << "a shader that ignored the weight would fail";
}

// A fading copy sends its record and the action it leaves: 32 bytes, the
// others 16, so a frame's records cost between 16 and 32 bytes a copy.
TEST(TransitionsOnTheGpu, BakedFadingCopiesSend32Bytes) {
  OPEN_GL_OR_SKIP(context);
  const Character& humanoid = default_humanoid();
  context->make_current();
  GlCrowdRenderer renderer(*context, humanoid, 160, small_fading_frame());
  CrowdBench bench(humanoid, fading_config("baked", &renderer, 160));
  Counters counters;
  for (size_t f = 0; f <= 40; ++f) counters = bench.step().counters;
  const size_t fading = fading_on_screen(bench.view());
  ASSERT_GT(fading, 0u);
  ASSERT_LT(fading, counters.copies_visible);
  EXPECT_EQ(counters.record_bytes_uploaded, counters.copies_visible * sizeof(GpuInstance) + fading * sizeof(GpuFade));
  const double per_copy = static_cast<double>(counters.record_bytes_uploaded) / counters.copies_visible;
  EXPECT_GT(per_copy, 16.0);
  EXPECT_LT(per_copy, 32.0);
  EXPECT_EQ(counters.draw_calls, 2u) << "the still copies' draw, and the fading copies'";
}

// The audit covers baked fading copies: their drawn pose (the mix of two
// baked records) against the exact blend of the two actions' local poses.
// Mixing matrices shortens a limb that turns far between the two actions, so
// the error is finite, and it is the fading copies' own (recomputed here); a
// shader that ignored the weight would stray further. Both crossfades.
TEST(TransitionsOnTheGpu, TheDrawnErrorAuditMeasuresBakedFadingCopies) {
  OPEN_GL_OR_SKIP(context);
  const Character& humanoid = default_humanoid();
  context->make_current();
  for (Crossfade crossfade : {Crossfade::Sampled, Crossfade::Frozen}) {
    GlCrowdRenderer renderer(*context, humanoid, 24, small_fading_frame());
    CrowdBench baked(humanoid, fading_config("baked", &renderer, 24, crossfade));
    CrowdBench exact(humanoid, fading_config("threaded", nullptr, 24, crossfade));
    for (size_t f = 0; f <= 40; ++f) baked.step(), exact.step();
    const DrawnErrorRecord error = baked.measure_drawn_error(kHeight);
    double right = 0, wrong = 0;
    const FrameView& view = baked.view();
    ASSERT_GT(fading_on_screen(view), 3u);
    for (size_t i = 0; i < view.copies(); ++i) {
      if (!view.visible[i] || !view.baked_fades[i].fading()) continue;
      const std::vector<glm::vec3> reference = skin_positions(humanoid.mesh, exact.skinning_matrices(i));
      right = std::max(right, largest_distance(skin_positions(humanoid.mesh, baked_drawn_palette(view, i)), reference));
      wrong = std::max(wrong,
                       largest_distance(skin_positions(humanoid.mesh, baked_drawn_palette(view, i, true)), reference));
    }
    std::cout << "[ info ] " << to_string(crossfade) << ": baked fading copies stray up to " << right
              << " units from their exact blend (audit: " << error.max << ", RMS " << error.rms
              << "); the weight ignored: " << wrong << "\n";
    EXPECT_GT(error.max, 0.0) << to_string(crossfade);
    EXPECT_NEAR(error.max, right, 1e-3 * right) << to_string(crossfade) << ": the largest error is a fading copy's mix";
    EXPECT_LT(error.max, wrong) << to_string(crossfade);
  }
}

// frozen holds the action left where the change found it: a fading copy's
// second slot keeps its position from frame to frame; sampled moves it on.
TEST(TransitionsOnTheGpu, FrozenBakedFadesHoldTheActionLeft) {
  OPEN_GL_OR_SKIP(context);
  const Character& humanoid = default_humanoid();
  context->make_current();
  for (Crossfade crossfade : {Crossfade::Frozen, Crossfade::Sampled}) {
    GlCrowdRenderer renderer(*context, humanoid, 24, small_fading_frame());
    CrowdBench bench(humanoid, fading_config("baked", &renderer, 24, crossfade));
    size_t held = 0, moved = 0;
    std::vector<BakedFade> last(bench.crowd().size());
    for (size_t f = 0; f <= 40; ++f) {
      bench.step();
      const FrameView& view = bench.view();
      for (size_t i = 0; i < view.copies(); ++i) {
        const BakedFade now = view.visible[i] ? view.baked_fades[i] : BakedFade{};
        if (now.fading() && last[i].fading() && now.first_sample == last[i].first_sample && now.weight < last[i].weight)
          (now.position == last[i].position ? held : moved) += 1;
        last[i] = now;
      }
    }
    std::cout << "[ info ] " << to_string(crossfade) << ": " << held << " fading frames held, " << moved << " moved\n";
    if (crossfade == Crossfade::Frozen) {
      EXPECT_GT(held, 10u);
      EXPECT_EQ(moved, 0u);
    } else {
      EXPECT_GT(moved, 10u);
      EXPECT_EQ(held, 0u);
    }
  }
}

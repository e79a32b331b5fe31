// Placements sent once (issue 52 item 3, render/gpu_placements.h): a copy's
// placement goes to the GPU with the first frame and again only where it
// changed; each frame a copy on screen sends at most a 16-byte record in
// instanced and baked, and frustum gpu's cull pass writes records as small.
// Counted by the counters the result's per-copy figures come from.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "frame/frame_view.h"
#include "render/gl_errors.h"
#include "render/gpu_frame_buffers.h"
#include "render/gpu_placements.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;
using namespace crowdprof::test;

namespace {

struct Case {
  const char* mode;
  FrustumTest frustum;
};

// Frames 0 and 1 of `copies` humanoids in `c`'s mode, on a renderer of their own.
std::array<Counters, 2> two_frames(GlContext& context, const Case& c, size_t copies) {
  context.make_current();
  RendererConfig rc;
  rc.width = kWidth;
  rc.height = kHeight;
  GlCrowdRenderer renderer(context, default_humanoid(), copies, rc);
  BenchConfig config;
  config.mode = find_mode(c.mode)->switches;
  config.mode.frustum = c.frustum;
  config.crowd.copies = copies;
  config.aspect = static_cast<float>(kWidth) / kHeight;
  config.renderer = &renderer;
  CrowdBench bench(default_humanoid(), config);
  Counters first = bench.step().counters;
  return {first, bench.step().counters};
}

}  // namespace

TEST(Placements, RecordsAreAtMost16BytesACopyOnScreenAndPlacementsGoOnce) {
  OPEN_GL_OR_SKIP(context);
  static_assert(sizeof(GpuInstance) <= 16, "a copy on screen sends at most 16 bytes a frame");
  const size_t copies = 40;
  for (const Case& c :
       {Case{"instanced", FrustumTest::Cpu}, Case{"baked", FrustumTest::Cpu}, Case{"baked", FrustumTest::Gpu}}) {
    const bool gpu_cull = c.frustum == FrustumTest::Gpu;
    const std::string what = std::string(c.mode) + (gpu_cull ? ", frustum gpu" : "");
    const auto [first, second] = two_frames(*context, c, copies);
    ASSERT_GT(second.copies_visible, 0u) << what;
    ASSERT_LT(second.copies_visible, copies) << what << ": the default camera leaves some copies out";
    const uint64_t commands = gpu_cull ? 20 : 0;  // frustum gpu's one command, cleared each frame
    // Frame 0: every copy's placement, on screen or not, besides the frame's palettes and records.
    EXPECT_EQ(first.bytes_uploaded,
              copies * sizeof(GpuPlacement) + first.palette_bytes_uploaded + first.record_bytes_uploaded + commands)
        << what;
    // Frame 1: the crowd has not moved, so no placement goes again.
    EXPECT_EQ(second.bytes_uploaded, second.palette_bytes_uploaded + second.record_bytes_uploaded + commands) << what;
    if (gpu_cull) {
      // The cull pass writes the records on the GPU; GpuCull refuses a
      // cull.comp whose records lie other than sizeof(GpuInstance) apart.
      EXPECT_EQ(second.record_bytes_uploaded, 0u) << what;
    } else {
      EXPECT_EQ(second.record_bytes_uploaded, 16 * second.copies_visible) << what;
    }
    EXPECT_EQ(second.palette_bytes_uploaded, std::string(c.mode) == "instanced" ? 3312 * second.copies_visible : 0)
        << what;
  }
}

// Past one uniform page of placements (1,362 copies in llvmpipe's 64 KiB
// blocks) a draw per page: instanced draws what CPU skinning draws, and
// CPU-culled baked what frustum gpu's draws read from one storage block.
TEST(Placements, PagesOfPlacementsDrawWhatOneBlockAndTheCpuDraw) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.copies = 2000;
  shot.frame = 1;
  Frame cpu = render(*context, thirty_bone_humanoid(), shot);
  shot.mode = "instanced";
  Frame instanced = render(*context, thirty_bone_humanoid(), shot);
  ASSERT_GT(instanced.counters.copies_visible, 1362u) << "copies on screen past the first page";
  EXPECT_EQ(instanced.counters.draw_calls, 2u) << "a draw a page of placements";
  shot.mode = "baked";
  Frame paged = render(*context, thirty_bone_humanoid(), shot);
  shot.frustum = FrustumTest::Gpu;
  Frame one_block = render(*context, thirty_bone_humanoid(), shot);
  EXPECT_EQ(paged.counters.draw_calls, 2u);
  EXPECT_EQ(one_block.counters.draw_calls, 1u);
  const size_t pixels = cpu.rgba.size() / 4;
  ASSERT_GT(covered(cpu.rgba), pixels / 200);
  EXPECT_LE(pixels_differing(cpu.rgba, instanced.rgba, 4) * 2000, pixels);
  EXPECT_LE(pixels_differing(one_block.rgba, paged.rgba, 4) * 2000, pixels);
}

TEST(Placements, AMovedCopyIsSentAgainAndOnlyIt) {
  OPEN_GL_OR_SKIP(context);
  context->make_current();
  GlFeatures gl;
  gl.max_storage_block_bytes = int64_t{128} << 20;
  gl.storage_offset_alignment = 16;
  std::vector<uint16_t> kind(5, 0);
  std::vector<glm::mat4> world(5, glm::mat4(1.0f));
  FrameView view;
  view.kind = kind;
  view.world = world;
  GpuPlacements placements;
  EXPECT_EQ(placements.update(view, gl), 5 * sizeof(GpuPlacement)) << "all, the first time";
  EXPECT_EQ(placements.update(view, gl), 0u);
  world[3] = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(placements.update(view, gl), sizeof(GpuPlacement)) << "the copy that moved";
  EXPECT_EQ(placements.update(view, gl), 0u);
  world[1] = world[4] = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
  EXPECT_EQ(placements.update(view, gl), 2 * sizeof(GpuPlacement));
  kind.push_back(0);
  world.push_back(glm::mat4(1.0f));
  view.kind = kind;
  view.world = world;
  EXPECT_EQ(placements.update(view, gl), 6 * sizeof(GpuPlacement)) << "a crowd of another size: all again";
  world[0][0][3] = 0.5f;
  EXPECT_THROW(placements.update(view, gl), GlError) << "a projective placement would lose its fourth row";
}

// Paged palettes (issue 30 item 2, lib/render/gpu_frame_buffers.h): palettes
// past one storage block are cut into pages, each bound as a range of one
// buffer. With storage blocks of 64 KiB (CROWDPROF_GL_HIDE=small-blocks: about
// 19 humanoid palettes a page) `buffer` and `instanced` draw the image they draw
// in one page, `instanced` with one draw per page; `baked` draws its records
// through instanced's path whatever the block; a crowd past the GPU's free
// memory is refused, naming the limit and how many copies would fit.
#include <gtest/gtest.h>

#include <string>

#include "render/gl_errors.h"
#include "render/gpu_frame_buffers.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;
using namespace crowdprof::test;

TEST(PagedPalettes, SmallBlocksDrawTheSameImage) {
  OPEN_GL_OR_SKIP(context);
  const Character* one[] = {&default_humanoid()};
  const Character* two[] = {&default_humanoid(), &thirty_bone_humanoid()};
  for (std::span<const Character* const> characters :
       {std::span<const Character* const>(one), std::span<const Character* const>(two)}) {
    for (const char* mode : {"buffer", "instanced"}) {
      const std::string what = std::string(mode) + ", " + std::to_string(characters.size()) + " character(s)";
      Shot shot;
      shot.mode = mode;
      shot.copies = 60;
      shot.frame = 2;
      Frame whole = render(*context, characters, shot);
      shot.hide_features = "small-blocks";
      Frame paged = render(*context, characters, shot);
      ASSERT_GT(whole.counters.copies_visible, 40u) << what << ": more palettes than two pages hold";
      EXPECT_EQ(paged.counters.copies_visible, whole.counters.copies_visible) << what;
      EXPECT_EQ(paged.digest, whole.digest) << what;
      const size_t pixels = whole.rgba.size() / 4;
      ASSERT_GT(covered(whole.rgba), pixels / 200) << what;
      EXPECT_EQ(pixels_differing(whole.rgba, paged.rgba, 4), 0u) << what;
      if (std::string(mode) == "instanced") {
        EXPECT_EQ(whole.counters.draw_calls, characters.size()) << what;
        // 64 KiB pages hold 19 humanoid palettes: at least one more draw per page past the first.
        EXPECT_GE(paged.counters.draw_calls, whole.counters.copies_visible / 19) << what;
      } else {
        EXPECT_EQ(paged.counters.draw_calls, whole.counters.draw_calls) << what;
      }
    }
  }
}

// More records than a 64 KiB block holds, and more placements than a 64 KiB
// uniform page (1,362 of 48 bytes): the records are vertex attributes and the
// placements are paged, so the crowd is drawn, not refused, and draws the
// image it draws with large storage blocks; baked draws through the same
// records (once, its placements lived in one storage block: a real GPU with
// 64 KiB blocks refused 1,000 instanced copies).
TEST(PagedPalettes, InstancedRecordsPastOneBlockAreDrawn) {
  OPEN_GL_OR_SKIP(context);
  for (const char* mode : {"instanced", "baked"}) {
    Shot shot;
    shot.mode = mode;
    shot.copies = 2000;
    shot.frame = 1;
    shot.bake_rate = 5.0f;  // 30 joints: at 30 Hz its table needs 198,720 bytes, at 5 Hz it fits 64 KiB
    Frame whole = render(*context, thirty_bone_humanoid(), shot);
    shot.hide_features = "small-blocks";
    Frame paged = render(*context, thirty_bone_humanoid(), shot);
    ASSERT_GT(whole.counters.copies_visible, 1362u) << mode;
    EXPECT_EQ(paged.counters.copies_visible, whole.counters.copies_visible) << mode;
    if (std::string(mode) == "baked") {
      // No palette to page: one draw a page of placements (llvmpipe's uniform blocks are 64 KiB).
      EXPECT_EQ(whole.counters.draw_calls, 2u);
      EXPECT_EQ(paged.counters.draw_calls, 2u);
    }
    EXPECT_EQ(paged.digest, whole.digest) << mode;
    ASSERT_GT(covered(whole.rgba), whole.rgba.size() / 4 / 200) << mode;
    EXPECT_EQ(pixels_differing(whole.rgba, paged.rgba, 4), 0u) << mode;
  }
}

// A baked table is one storage block in the vertex shader: one larger than the
// GL's block is refused at load, naming the limit and what to change.
TEST(PagedPalettes, ABakedTablePastOneBlockIsRefusedNamingTheLimit) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.mode = "baked";
  shot.copies = 4;
  shot.hide_features = "small-blocks";
  try {
    render(*context, default_humanoid(), shot);  // 69 joints: 3,312 bytes a sample, 64 KiB hold 19
    ADD_FAILURE() << "a table past the block was accepted";
  } catch (const GlUnavailable& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << what;
    EXPECT_NE(what.find("65536"), std::string::npos) << what;
    EXPECT_NE(what.find("bake_rate"), std::string::npos) << what << ": says what to change";
  }
}

TEST(PagedPalettes, ACrowdPastTheGpusFreeMemoryIsRefusedSayingHowManyFit) {
  OPEN_GL_OR_SKIP(context);
  GlFeatures gl;
  gl.vertex_storage_blocks = 16;
  gl.max_storage_block_bytes = int64_t{128} << 20;
  gl.storage_offset_alignment = 16;
  gl.memory_free_kib = 1024;  // 1 MiB free
  gl.memory_source = "NVX_gpu_memory_info";
  GpuFrameBuffers buffers;
  // 1,000 humanoids: 69 joints, 207 rows (3,312 bytes) and a 16-byte record each.
  try {
    buffers.reserve(1000, 1000 * 207, 207, true, gl);
    FAIL() << "1,000 palettes reserved in 1 MiB";
  } catch (const GlUnavailable& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("1000 copies need 3.1 MiB"), std::string::npos) << what;
    EXPECT_NE(what.find("the GPU has 1.0 MiB free (NVX_gpu_memory_info)"), std::string::npos) << what;
    EXPECT_NE(what.find("room for about 315 copies"), std::string::npos) << what;  // 1,048,576 / 3,328
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  // Not said: nothing is refused for memory (the GL's own out-of-memory error would be).
  gl.memory_free_kib = -1;
  EXPECT_NO_THROW(buffers.reserve(1000, 1000 * 207, 207, true, gl));
  // The records are vertex attributes, not a storage block: 16,000 bytes of
  // them need no 64 KiB block (a real GPU with 64 KiB blocks once refused
  // 1,000 instanced copies here).
  gl.max_storage_block_bytes = 64 << 10;
  EXPECT_NO_THROW(buffers.reserve(1000, 1000 * 207, 207, true, gl));
  // Mode buffer sends no records: only its palettes count.
  EXPECT_NO_THROW(buffers.reserve(1000, 1000 * 207, 207, false, gl));
  // A palette larger than a page, however small the others (a mixed crowd).
  try {
    buffers.reserve(2, 207 + 5000, 5000, false, gl);
    FAIL() << "a 5,000-row palette in 4,096-row pages";
  } catch (const GlUnavailable& e) {
    EXPECT_NE(std::string(e.what()).find("a palette of 1666 joints needs 78.1 KiB"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("holds 64.0 KiB"), std::string::npos) << e.what();
  }
}

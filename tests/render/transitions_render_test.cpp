// Transitions on the GPU (issue 53 item 3): the GPU palette modes draw the
// blended palettes the CPU built.
#include <gtest/gtest.h>

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

}  // namespace

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

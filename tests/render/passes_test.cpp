// Passes (issue 30 items 3 and 4): the crowd drawn into a depth prepass and
// shadow cascades before colour. The colour image is the one without passes
// in every mode; vertex-shader skinning repeats per pass and compute skinning
// does not, which the pipeline statistics show; each pass is timed, and the
// passes add up to no more than the frame's GPU time.
#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.h"
#include "base/modes.h"
#include "render/gl_features.h"
#include "render_support.h"
#include "test_support.h"

using namespace crowdprof;
using namespace crowdprof::test;

namespace {

constexpr const char* kDrawnModes[] = {"threaded", "hwskin", "buffer", "instanced", "compute", "baked"};

double stat(const GpuTime& t, GpuPass pass, PipelineStat s) {
  return t.passes.stats[static_cast<size_t>(pass)][static_cast<size_t>(s)];
}

}  // namespace

TEST(Passes, TheColourImageIsTheOneWithoutPassesInEveryMode) {
  OPEN_GL_OR_SKIP(context);
  for (const char* mode : kDrawnModes) {
    Shot shot;
    shot.mode = mode;
    shot.copies = 8;
    shot.camera = "close";
    Frame one = render(*context, default_humanoid(), shot);
    shot.passes = 4;  // prepass, 2 cascades, colour
    Frame four = render(*context, default_humanoid(), shot);
    size_t pixels = one.rgba.size() / 4;
    ASSERT_GT(covered(one.rgba), pixels / 200) << mode;
    size_t differing = pixels_differing(one.rgba, four.rgba, 4);
    std::cout << "[ info ] " << mode << ": " << differing << " of " << pixels << " pixels differ with 4 passes\n";
    EXPECT_LE(differing * 2000, pixels) << mode;
    EXPECT_EQ(four.digest, one.digest) << mode << ": passes change what is drawn, not the animation";
    EXPECT_EQ(four.counters.draw_calls, 4 * one.counters.draw_calls) << mode;
  }
}

TEST(Passes, VertexShaderSkinningSendsPalettesPerPassAndBuffersOnce) {
  OPEN_GL_OR_SKIP(context);
  Shot shot;
  shot.copies = 8;
  shot.camera = "close";
  shot.mode = "hwskin";
  Frame one = render(*context, default_humanoid(), shot);
  shot.passes = 3;
  Frame three = render(*context, default_humanoid(), shot);
  EXPECT_EQ(three.counters.bytes_uploaded, 3 * one.counters.bytes_uploaded) << "a uniform palette per draw";
  for (const char* mode : {"buffer", "compute", "threaded"}) {
    shot.mode = mode;
    shot.passes = 1;
    Frame single = render(*context, default_humanoid(), shot);
    shot.passes = 3;
    Frame triple = render(*context, default_humanoid(), shot);
    uint64_t visible = single.counters.copies_visible;
    // Palettes or vertices go up once; the model matrix goes with each draw.
    EXPECT_EQ(triple.counters.bytes_uploaded, single.counters.bytes_uploaded + 2 * visible * 64) << mode;
  }
}

TEST(Passes, PipelineStatisticsShowWhichSkinningRepeatsPerPass) {
  OPEN_GL_OR_SKIP(context);
  if (!read_gl_features().timer_queries()) GTEST_SKIP() << "no GL timer queries here";
  if (!read_gl_features().pipeline_statistics) GTEST_SKIP() << "no ARB_pipeline_statistics_query here";
  auto last = [&](const std::string& mode, uint32_t passes) {
    Shot shot;
    shot.mode = mode;
    shot.copies = 8;
    shot.frame = 3;
    shot.passes = passes;
    Frame f = render(*context, default_humanoid(), shot);
    EXPECT_FALSE(f.gpu_times.empty()) << mode;
    return f.gpu_times.empty() ? GpuTime{} : f.gpu_times.back();
  };
  for (const char* mode : {"hwskin", "compute"}) {
    GpuTime one = last(mode, 1), four = last(mode, 4);
    ASSERT_TRUE(four.passes.has_stats()) << mode;
    double colour = stat(four, GpuPass::Colour, PipelineStat::VerticesSubmitted);
    EXPECT_GT(colour, 0) << mode;
    EXPECT_EQ(stat(four, GpuPass::Prepass, PipelineStat::VerticesSubmitted), colour) << mode;
    EXPECT_EQ(stat(four, GpuPass::Shadows, PipelineStat::VerticesSubmitted), 2 * colour) << mode << ": 2 cascades";
    EXPECT_EQ(stat(one, GpuPass::Prepass, PipelineStat::VerticesSubmitted), 0) << mode << ": no prepass";
    EXPECT_EQ(stat(one, GpuPass::Colour, PipelineStat::VerticesSubmitted), colour) << mode;
    // Compute skins each vertex once a frame, whatever the passes; the vertex
    // shader's skinning runs in every pass's vertex invocations.
    double skinned_one = stat(one, GpuPass::Skinning, PipelineStat::ComputeShaderInvocations);
    double skinned_four = stat(four, GpuPass::Skinning, PipelineStat::ComputeShaderInvocations);
    if (std::string(mode) == "compute") {
      EXPECT_GE(skinned_one, 8.0 * 4951) << "every vertex of every copy on screen";
      EXPECT_EQ(skinned_four, skinned_one);
    } else {
      EXPECT_EQ(skinned_four, 0);
    }
    // Each drawn pass is timed; the passes fit in the frame's GPU time.
    double sum = 0;
    for (size_t p = 0; p < kGpuPassCount; ++p) {
      EXPECT_GE(four.passes.ms[p], 0) << mode << " " << kGpuPassNames[p];
      sum += four.passes.ms[p];
    }
    EXPECT_LE(sum, four.ms * 1.001 + 1e-3) << mode;
  }
}

TEST(Passes, WithoutABackendThePassesSwitchIsRefused) {
  BenchConfig config;
  config.mode = find_mode("threaded")->switches;
  config.mode.passes = 2;
  SettingText why = why_cannot_run(config);
  EXPECT_NE(why.str().find("passes 2 draws the crowd several times a frame, which needs a GL backend"),
            std::string::npos)
      << why.str();
  config.mode.passes = 1;
  EXPECT_TRUE(why_cannot_run(config).empty());
}

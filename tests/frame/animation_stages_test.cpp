// Animations by stage (issue 53 item 4): each stage's thread time follows the
// work the mode does, fits inside the Animations category on one thread, and
// reaches the result, the text report, the CSV and the trace.
#include <gtest/gtest.h>

#include <numeric>
#include <sstream>

#include "frame/crowd_bench.h"
#include "measuring/trace.h"
#include "render_support.h"
#include "reports/profile_table.h"

using namespace crowdprof;

namespace {

BenchConfig config_of(const std::string& mode, double transitions_s, int threads = 1) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode.transitions_s = transitions_s;
  config.mode.blend_in_s = transitions_s > 0 ? 0.4 : config.mode.blend_in_s;
  config.mode_name = mode;
  config.threads = threads;
  config.crowd.copies = 40;
  config.crowd.actions = ActionChoice::Random;
  return config;
}

double stage(const FrameRecord& f, AnimationStage s) {
  return f.animation_stages.ms[static_cast<size_t>(s)];
}
double animations(const FrameRecord& f) {
  return f.times[Category::Animations];
}

}  // namespace

TEST(AnimationStages, EachStageIsTimedWhereItsWorkRuns) {
  // Master skins in Rasterizer: no skinning in Animations; threaded skins there.
  CrowdBench master(test::default_humanoid(), config_of("master", 0));
  CrowdBench threaded(test::default_humanoid(), config_of("threaded", 0, 2));
  for (int f = 0; f < 5; ++f) {
    const FrameRecord m = master.step(), t = threaded.step();
    EXPECT_GT(stage(m, AnimationStage::Sampling), 0);
    EXPECT_GT(stage(m, AnimationStage::LocalToModel), 0);
    EXPECT_EQ(stage(m, AnimationStage::Skinning), 0) << "master skins under Rasterizer";
    EXPECT_EQ(stage(m, AnimationStage::Blending), 0) << "no transitions, nothing blended";
    EXPECT_GT(stage(t, AnimationStage::Skinning), 0);
    EXPECT_EQ(stage(t, AnimationStage::Blending), 0);
  }
}

TEST(AnimationStages, FadesAreTimedAsBlendingAndOnlyThen) {
  CrowdBench bench(test::default_humanoid(), config_of("culled", 1.0));
  size_t fading_frames = 0;
  for (int f = 0; f < 120; ++f) {
    const FrameRecord r = bench.step();
    if (r.counters.fades == 0) {
      EXPECT_EQ(stage(r, AnimationStage::Blending), 0) << "frame " << f;
      continue;
    }
    ++fading_frames;
    EXPECT_GT(stage(r, AnimationStage::Blending), 0) << "frame " << f;
  }
  EXPECT_GT(fading_frames, 10u);
}

TEST(AnimationStages, OnOneThreadTheStagesFitInsideAnimations) {
  CrowdBench bench(test::default_humanoid(), config_of("culled", 1.0));
  for (int f = 0; f < 60; ++f) {
    const FrameRecord r = bench.step();
    // Both read one steady clock, the stages strictly inside the category (how
    // much of it they are depends on the machine's load: not tested).
    EXPECT_LE(r.animation_stages.total_ms(), animations(r) + 1e-6) << "frame " << f;
    EXPECT_GT(r.animation_stages.total_ms(), 0) << "frame " << f;
  }
}

TEST(AnimationStages, TheSplitReachesTheResultTheReportAndTheCsv) {
  CrowdBench bench(test::default_humanoid(), config_of("threaded", 1.0, 2));
  Result result;
  result.run.threads = 2;
  result.run.switches = config_of("threaded", 1.0, 2).mode;
  result.run.characters = 40;
  for (int f = 0; f < 90; ++f) result.frame_records.push_back(bench.step());
  record_samples(result);
  std::optional<AnimationSplit> split = animation_split(result);
  ASSERT_TRUE(split);
  EXPECT_EQ(split->threads, 2);
  EXPECT_NEAR(std::accumulate(split->share.begin(), split->share.end(), 0.0), 1.0, 1e-9);
  EXPECT_GT(split->coverage, 0);
  EXPECT_LE(split->coverage, 1.0 + 1e-6) << "thread time within Animations' wall time x threads";
  const std::string text = format_profile(result);
  EXPECT_NE(text.find("Animations by stage: sampling "), std::string::npos) << text;
  EXPECT_NE(text.find(" fades, "), std::string::npos) << "the work line counts fades with transitions on";
  std::ostringstream csv;
  write_csv(result, csv);
  std::istringstream lines(csv.str());
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  EXPECT_NE(
      header.find(",animation_sampling_ms,animation_blending_ms,animation_local_to_model_ms,animation_skinning_ms"),
      std::string::npos);
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), std::count(row.begin(), row.end(), ','));
}

TEST(AnimationStages, ATraceNestsEachStageInItsTask) {
  Tracer tracer;
  BenchConfig config = config_of("threaded", 1.0, 2);
  config.tracer = &tracer;
  CrowdBench bench(test::default_humanoid(), config);
  for (int f = 0; f < 60; ++f) bench.step();
  size_t sampling = 0, blending = 0;
  for (const TraceSpan& span : tracer.spans()) {
    if (span.category != "animation") continue;
    sampling += span.name == "sampling";
    blending += span.name == "blending";
  }
  EXPECT_GE(sampling, 60u * 30u) << "a sampling span per copy posed per frame";
  EXPECT_GT(blending, 0u);
}

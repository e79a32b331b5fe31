// The culling audit of a whole bench (issue 29 item 3): the run's own box is
// conservative on the thesis scene (never a false cull), the audit covers
// every copy at every pose it says, and a run's report carries it.
#include <gtest/gtest.h>

#include "frame/crowd_bench.h"
#include "frame/run_bench.h"
#include "reports/profile_table.h"
#include "render_support.h"

using namespace crowdprof;

namespace {

BenchConfig audit_config(const std::string& mode, size_t copies) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode_name = mode;
  config.threads = 2;
  config.crowd.copies = copies;
  return config;
}

const CullBoxAudit& box(const CullingAudit& audit, CullBox b) {
  return audit.boxes[static_cast<size_t>(b)];
}

}  // namespace

TEST(CullingAuditBench, TheRunsOwnBoxNeverCullsACopyInView) {
  BenchConfig config = audit_config("threaded", 160);
  config.crowd.actions = ActionChoice::Random;
  CrowdBench bench(test::default_humanoid(), config);
  bench.step();
  const CullingAudit audit = bench.audit_culling();
  EXPECT_EQ(audit.copies, 160u);
  EXPECT_EQ(audit.frames, 16u);
  EXPECT_EQ(audit.in_view + audit.outside + audit.undecided, 160u * 16u);
  // The default camera leaves the crowd's far corners out of view.
  EXPECT_GT(audit.outside, 0u);
  EXPECT_GT(audit.in_view, audit.outside);
  EXPECT_EQ(box(audit, CullBox::EveryAction).false_culls, 0u);
  EXPECT_EQ(box(audit, CullBox::OwnAction).false_culls, 0u);
  EXPECT_EQ(box(audit, CullBox::Tight).false_culls, 0u);
  // Looser boxes draw more: the tight box keeps fewest, every action's the most.
  EXPECT_LE(box(audit, CullBox::Tight).drawn, box(audit, CullBox::OwnAction).drawn);
  EXPECT_LE(box(audit, CullBox::OwnAction).drawn, box(audit, CullBox::EveryAction).drawn);
  EXPECT_GE(box(audit, CullBox::EveryAction).slack_mean, box(audit, CullBox::OwnAction).slack_mean);
  EXPECT_NEAR(box(audit, CullBox::Tight).slack_mean, 1.0, 1e-9);
  // The frame culled with the same box the audit calls every_action.
  uint64_t culled_now = 0;
  for (size_t i = 0; i < bench.crowd().size(); ++i) culled_now += !bench.visible(i);
  EXPECT_GT(culled_now, 0u);
}

TEST(CullingAuditBench, LargeCrowdsAreSampledWithinTheBound) {
  CrowdBench bench(test::default_humanoid(), audit_config("threaded", 1000));
  const CullingAudit audit = bench.audit_culling(4000);
  EXPECT_EQ(audit.copies, 1000u);
  EXPECT_EQ(audit.frames, 4u);
  const CullingAudit strided = bench.audit_culling(500);
  EXPECT_EQ(strided.copy_stride, 2u);
  EXPECT_EQ(strided.copies, 500u);
  EXPECT_EQ(strided.frames, 1u);
}

TEST(CullingAuditBench, TheReportCarriesItAndSaysItUnderTheTable) {
  CrowdBench bench(test::default_humanoid(), audit_config("culled", 40));
  RunOptions options;
  options.frames = 2;
  options.warmup = 0;
  Result report = run_bench(bench, "humanoid.glb", options);
  ASSERT_TRUE(report.culling_audit);
  EXPECT_EQ(report.culling_audit->copies, 40u);
  EXPECT_GT(report.culling_audit->ms, 0.0) << "the audit's own time, measured where it runs";
  const std::string text = format_profile(report);
  EXPECT_NE(text.find("culling audit (16 exact poses of 40 copies in "), std::string::npos) << text;
  EXPECT_NE(text.find("every-action (this run's) 0 false culls"), std::string::npos) << text;
}

// check's first step without a process: what the gate compares, how many runs,
// and every value checked by setting name.
#include <gtest/gtest.h>

#include "asset/errors.h"
#include "profile/check_plan.h"

namespace {

using namespace crowdprof;

TEST(CheckPlan, Defaults) {
  CheckPlan plan = plan_check({});
  EXPECT_EQ(plan.gate.metrics, std::vector<std::string>{"calibrated"});
  EXPECT_DOUBLE_EQ(plan.gate.tolerance, 0.07);
  EXPECT_EQ(plan.runs, 8u);
  EXPECT_EQ(plan.spread_s, 0.0);
  EXPECT_TRUE(plan.gate.compare_work);
  CheckRequest update;
  update.update_baseline = true;
  EXPECT_EQ(plan_check(update).runs, 20u);  // a baseline's luck counts at every later check
  update.runs = 3;
  EXPECT_EQ(plan_check(update).runs, 3u);
}

TEST(CheckPlan, MetricsResolveOnceEach) {
  CheckRequest request;
  request.metrics = {"frame", "Animations", "frame_ms", "animations"};
  EXPECT_EQ(plan_check(request).gate.metrics, (std::vector<std::string>{"frame_ms", "animations_ms"}));
  request.metrics = {"all", "frame"};
  CheckPlan all = plan_check(request);
  EXPECT_EQ(all.gate.metrics, all_metrics());
}

TEST(CheckPlan, BadValuesNameTheirSetting) {
  auto setting = [](CheckRequest request) -> std::string {
    try {
      plan_check(request);
    } catch (const SettingError& e) {
      return e.name;
    }
    return "accepted";
  };
  CheckRequest r;
  r.tolerance = "lots";
  EXPECT_EQ(setting(r), "tolerance");
  r = {};
  r.floor = "-1%";
  EXPECT_EQ(setting(r), "floor");
  r = {};
  r.alpha = 1.5;
  EXPECT_EQ(setting(r), "alpha");
  r = {};
  r.runs = 0;
  EXPECT_EQ(setting(r), "runs");
  r = {};
  r.spread_s = -1;
  EXPECT_EQ(setting(r), "spread");
  r = {};
  r.metrics = {"speed"};
  EXPECT_EQ(setting(r), "metric");
  r = {};
  r.timings_only = r.update_baseline = true;
  EXPECT_THROW(plan_check(r), UsageError);
}

}  // namespace

// check's first step without a process: what the gate compares, how many runs,
// and every value checked by setting name.
#include <gtest/gtest.h>

#include "base/errors.h"
#include "gate/check_plan.h"

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

// A result of three frames with CPU time, calibrated by probe `probe` (0: not).
Result timed(int probe) {
  Result r;
  r.samples.frame_ms = {2.0, 2.1, 2.2};
  r.samples.cpu_ms = {3.0, 3.1, 3.2};
  if (probe > 0) {
    r.calibration_probe = probe;
    r.samples.probe_ms = {4.0, 4.0, 4.0};
    r.samples.calibrated = {0.5, 0.525, 0.55};
  }
  return r;
}

TEST(GateMetrics, CalibratedWhereBothRanOneProbe) {
  GateMetrics m = gate_metrics(timed(1), timed(1), {"calibrated"}, false, "base.json", "the run");
  EXPECT_EQ(m.metrics, std::vector<std::string>{"calibrated"});
  EXPECT_TRUE(m.notes.empty());
}

TEST(GateMetrics, UnnamedCalibratedFallsBackAndSaysWhy) {
  // Neither calibrated: CPU time compares like for like.
  GateMetrics neither = gate_metrics(timed(0), timed(0), {"calibrated"}, false, "base.json", "the run");
  EXPECT_EQ(neither.metrics, std::vector<std::string>{"cpu_ms"});
  ASSERT_EQ(neither.notes.size(), 1u);
  EXPECT_NE(neither.notes[0].find("base.json has no calibrated frame time"), std::string::npos) << neither.notes[0];
  // Only one ran the probe, which slows the frame after it: nothing timed
  // compares, unless named.
  try {
    gate_metrics(timed(0), timed(1), {"calibrated"}, false, "base.json", "the run");
    ADD_FAILURE() << "one side probed, the other not, compared";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "base.json: was timed without the calibration probe between frames and the run with it: the probe "
                 "slows the frame after it, so no timed metric compares like for like; time both alike (bench "
                 "--calibrate or check --json for both, or neither), or name a --metric to compare anyway");
  }
  EXPECT_THROW(gate_metrics(timed(1), timed(0), {"calibrated"}, false, "base.json", "now.json"), InputError);
  GateMetrics one = gate_metrics(timed(0), timed(1), {"frame_ms"}, true, "base.json", "the run");
  EXPECT_EQ(one.metrics, std::vector<std::string>{"frame_ms"});
  ASSERT_EQ(one.notes.size(), 1u);
  EXPECT_EQ(one.notes[0].rfind("warning: only one of the two ran the calibration probe", 0), 0u) << one.notes[0];
  // Two probe versions: CPU time, as both ran a probe.
  GateMetrics versions = gate_metrics(timed(1), timed(2), {"calibrated"}, false, "base.json", "the run");
  EXPECT_EQ(versions.metrics, std::vector<std::string>{"cpu_ms"});
  EXPECT_NE(versions.notes[0].find("different probes (version 1 and 2)"), std::string::npos) << versions.notes[0];
  // Neither has CPU time: the frame.
  Result no_cpu = timed(0);
  no_cpu.samples.cpu_ms.clear();
  EXPECT_EQ(gate_metrics(no_cpu, timed(0), {"calibrated"}, false, "b", "r").metrics,
            std::vector<std::string>{"frame_ms"});
}

TEST(GateMetrics, NamedMetricsAreNeverSwapped) {
  // --metric calibrated over two probe versions: an error naming the baseline.
  try {
    gate_metrics(timed(1), timed(2), {"calibrated"}, true, "base.json", "the run");
    FAIL() << "two probe versions compared";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("base.json: was calibrated by probe version 1, the run by version 2"),
              std::string::npos)
        << e.what();
  }
  // --metric cpu with one calibrated run: kept, with a note.
  GateMetrics cpu = gate_metrics(timed(0), timed(1), {"cpu_ms"}, true, "base.json", "the run");
  EXPECT_EQ(cpu.metrics, std::vector<std::string>{"cpu_ms"});
  ASSERT_EQ(cpu.notes.size(), 1u);
  EXPECT_NE(cpu.notes[0].find("no timed metric compares like for like"), std::string::npos) << cpu.notes[0];
  // Named calibrated where one lacks it is left to the gate's own error.
  EXPECT_EQ(gate_metrics(timed(0), timed(1), {"calibrated"}, true, "b", "r").metrics,
            std::vector<std::string>{"calibrated"});
}

}  // namespace

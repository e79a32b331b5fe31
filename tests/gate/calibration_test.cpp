// The calibrated frame (issue 25 item 3): a fixed probe timed right after each
// frame, and the frame over it, which check compares by default. What CI can
// assert is the work and the bookkeeping, never a timed verdict.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "frame/calibration_probe.h"
#include "gate/check_options.h"
#include "gate/regression.h"
#include "result/result_codec.h"
#include "test_support.h"

using namespace crowdprof;
using nlohmann::json;

namespace {

std::string humanoid() {
  return (test::source_dir() / "scenes" / "humanoid.glb").string();
}

TEST(Calibration, TheProbeDoesTheSameWorkEveryRunOnAnyThreadCount) {
  CalibrationProbe one(1), two(2);
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(one.run(), 0.0);
    EXPECT_GT(two.run(), 0.0);
  }
  // The same output, whichever threads skinned it.
  EXPECT_EQ(one.checksum(), two.checksum());
  EXPECT_TRUE(std::isfinite(one.checksum()));
}

TEST(Calibration, ACalibratedBenchRecordsTheProbeAndDoesTheSameWork) {
  auto dir = test::scratch_dir("calibration_bench");
  std::string plain = (dir / "plain.json").string(), calibrated = (dir / "calibrated.json").string();
  std::string common = "bench '" + humanoid() + "' -n 6 --frames 6 --warmup 1 --mode threaded --threads 2 -q ";
  ASSERT_EQ(test::run_cli(common + "--json '" + plain + "'").status, 0);
  auto r = test::run_cli(common + "--calibrate --json '" + calibrated + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  json a = test::read_json(plain), b = test::read_json(calibrated);
  EXPECT_FALSE(a["samples"].contains("probe_ms"));
  EXPECT_FALSE(a.contains("calibration"));
  EXPECT_EQ(a["digest"], b["digest"]);
  EXPECT_EQ(a["counters"], b["counters"]);
  EXPECT_EQ(b["calibration"]["probe"], kCalibrationProbeVersion);
  std::vector<double> frame = b["samples"]["frame_ms"], probe = b["samples"]["probe_ms"],
                      ratio = b["samples"]["calibrated"];
  ASSERT_EQ(probe.size(), 6u);
  ASSERT_EQ(ratio.size(), 6u);
  for (size_t i = 0; i < probe.size(); ++i) {
    EXPECT_GT(probe[i], 0.0);
    EXPECT_DOUBLE_EQ(ratio[i], frame[i] / probe[i]);
    // The probe runs between frames and is charged to none of them.
    EXPECT_LT(frame[i], probe[i] * 50) << "frame " << i;
  }
  Result read = read_result(calibrated);
  ASSERT_NE(metric_samples(read, "calibrated"), nullptr);
  EXPECT_EQ(recorded_metrics(read).at(2), "calibrated");
  EXPECT_EQ(read.calibration_probe, kCalibrationProbeVersion);
}

TEST(Calibration, TheRatioIsDerivedFromTheFramesNeverTrustedFromTheFile) {
  auto dir = test::scratch_dir("calibration_codec");
  std::string path = (dir / "run.json").string();
  ASSERT_EQ(test::run_cli("bench '" + humanoid() + "' -n 2 --frames 4 --warmup 0 --calibrate -q --json '" + path + "'")
                .status,
            0);
  json doc = test::read_json(path);
  for (json& v : doc["samples"]["calibrated"]) v = 1000.0;
  Result tampered = read_result(test::write_json(dir / "tampered.json", doc));
  for (size_t i = 0; i < tampered.frames(); ++i)
    EXPECT_DOUBLE_EQ(tampered.samples.calibrated[i], tampered.samples.frame_ms[i] / tampered.samples.probe_ms[i]);
  doc["samples"]["probe_ms"][1] = 0;
  EXPECT_THROW(read_result(test::write_json(dir / "zero.json", doc)), InputError);
  doc["samples"]["probe_ms"][1] = 1e-320;  // above 0, but a frame over it is not a number
  EXPECT_THROW(read_result(test::write_json(dir / "denormal.json", doc)), InputError);
  doc["samples"]["probe_ms"].erase(1);
  EXPECT_THROW(read_result(test::write_json(dir / "short.json", doc)), InputError);
}

TEST(Calibration, TheFloorOfTheRatioIsAShareOfItsOwnMedian) {
  Result base, slower;
  for (double f : {1.0, 1.01, 0.99, 1.0, 1.02, 0.98, 1.0, 1.0, 1.01, 0.99}) {
    base.samples.frame_ms.push_back(f);
    base.samples.probe_ms.push_back(4.0);
    slower.samples.frame_ms.push_back(f * 1.2);
    slower.samples.probe_ms.push_back(4.0);
  }
  base.samples.calibrated = calibrated_frames(base.samples.frame_ms, base.samples.probe_ms);
  slower.samples.calibrated = calibrated_frames(slower.samples.frame_ms, slower.samples.probe_ms);
  CheckOptions options;
  options.compare_work = false;
  ASSERT_EQ(options.metrics, std::vector<std::string>{"calibrated"});
  CheckResult result = check_results(base, slower, options);
  ASSERT_EQ(result.metrics.size(), 1u);
  EXPECT_TRUE(result.metrics[0].regressed);
  EXPECT_EQ(result.metrics[0].value_unit, "probes");
  EXPECT_NEAR(result.metrics[0].floor_ms, 0.02 * 0.25, 1e-12);  // 2% of the baseline's 0.25
  EXPECT_NE(format_check(result, options).find("REGRESSION calibrated: median 0.25 probes -> 0.3 probes"),
            std::string::npos)
      << format_check(result, options);
  // A machine a fifth slower for both the frame and the probe is no regression.
  for (double& ms : slower.samples.probe_ms) ms *= 1.2;
  slower.samples.calibrated = calibrated_frames(slower.samples.frame_ms, slower.samples.probe_ms);
  EXPECT_FALSE(check_results(base, slower, options).regressed());
}

TEST(Calibration, CheckFallsBackToCpuTimeForAResultWithoutTheProbe) {
  auto dir = test::scratch_dir("calibration_fallback");
  std::string plain = (dir / "plain.json").string();
  ASSERT_EQ(test::run_cli("bench '" + humanoid() + "' -n 2 --frames 10 --warmup 0 -q --json '" + plain + "'").status,
            0);
  auto r = test::run_cli("check --result '" + plain + "' --baseline '" + plain + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("has no calibrated frame time (recorded by an older crowdprof or by bench without "
                       "--calibrate): checking cpu instead"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out.rfind("ok cpu", 0), 0u) << r.out;
  // Asked for by name, its absence is the result's fault (exit 3).
  r = test::run_cli("check --result '" + plain + "' --baseline '" + plain + "' --metric calibrated");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("samples.calibrated"), std::string::npos) << r.err;
}

// Timings compare only when both results ran the probe or neither did (it
// slows the frame after it, and its workers spin on into it), and the
// calibrated frame only between runs of the same probe version.
TEST(Calibration, APairThatCannotCompareTheCalibratedFrameFallsBackAndSaysWhy) {
  auto dir = test::scratch_dir("calibration_pairs");
  std::string plain = (dir / "plain.json").string(), calibrated = (dir / "calibrated.json").string();
  std::string common = "bench '" + humanoid() + "' -n 2 --frames 10 --warmup 0 -q ";
  ASSERT_EQ(test::run_cli(common + "--json '" + plain + "'").status, 0);
  ASSERT_EQ(test::run_cli(common + "--calibrate --json '" + calibrated + "'").status, 0);
  auto r = test::run_cli("check --result '" + calibrated + "' --baseline '" + plain + "' --tolerance 900%");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(r.err, "crowdprof: " + plain + ": was timed without the calibration probe between frames and " +
                       calibrated +
                       " with it: the probe slows the frame after it, so no timed metric compares like "
                       "for like; time both alike (bench --calibrate or check --json for both, or neither), or "
                       "name a --metric to compare anyway\n");
  EXPECT_TRUE(r.out.empty()) << r.out;
  r = test::run_cli("check --result '" + calibrated + "' --baseline '" + plain + "' --metric cpu --tolerance 900%");
  // Compared anyway (its verdict is the probe's doing, either way: not asserted).
  EXPECT_NE(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("crowdprof: warning: only one of the two ran the calibration probe"), std::string::npos)
      << r.err;

  json other = test::read_json(calibrated);
  other["calibration"]["probe"] = kCalibrationProbeVersion + 1;
  std::string other_path = test::write_json(dir / "other_probe.json", other);
  r = test::run_cli("check --result '" + calibrated + "' --baseline '" + other_path + "' --tolerance 900%");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("the two were calibrated by different probes (version " +
                       std::to_string(kCalibrationProbeVersion + 1) + " and " +
                       std::to_string(kCalibrationProbeVersion) + "): checking cpu instead"),
            std::string::npos)
      << r.err;
  r = test::run_cli("check --result '" + calibrated + "' --baseline '" + other_path + "' --metric calibrated");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("the calibrated frame does not compare"), std::string::npos) << r.err;
}

TEST(Calibration, TheAbRefusesTheCalibratedMetricBeforeAnythingRuns) {
  auto r =
      test::run_cli("check '" + humanoid() + "' -n 2 --frames 2 --against /nonexistent/crowdprof --metric calibrated");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--metric calibrated is for a stored baseline"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace

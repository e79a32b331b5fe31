// A timed baseline's work witness from the outside (issue 50 item 5): the
// baseline holds instructions per frame counted over a few frames; a check
// that runs slower counts this build's and fails at once when they grew, and
// warns instead of failing when they did not and the machine was seen to
// differ (here: the calibration probe, whose work never changes, recorded as
// 100 times as fast in the baseline). The baseline's frames are made 10,000
// times faster (or slower): a 6-copy frame lasts hundredths of a millisecond,
// and a loaded test machine moved its calibrated median 28-fold between the
// recording and the check. Skipped where nothing counts instructions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.h"

using crowdprof::test::humanoid_glb;
using crowdprof::test::read_json;
using crowdprof::test::run_cli;
using crowdprof::test::write_json;
using nlohmann::json;

namespace {

// Every run median of `key` times `factor`, and the median run's samples.
void scale_runs(json& doc, const char* key, double factor) {
  for (json& v : doc["runs"]["median_ms"][key]) v = v.get<double>() * factor;
  for (json& v : doc["samples"][key]) v = v.get<double>() * factor;
}

}  // namespace

TEST(WorkWitnessCli, ASlowerCheckCountsItsWorkAndWarnsOnlyWhenTheMachineChanged) {
  auto dir = crowdprof::test::scratch_dir("work_witness");
  const std::string base = (dir / "base.json").string();
  const std::string run = "check --spread 0 --confirm-spread 0 --runs 8 -q ";
  auto r =
      run_cli(run + "'" + humanoid_glb() + "' -n 6 --frames 8 --warmup 1 --baseline '" + base + "' --update-baseline");
  ASSERT_EQ(r.status, 0) << r.err;
  json recorded = read_json(base);
  if (!recorded.contains("instructions")) GTEST_SKIP() << "nothing counts instructions here: " << r.err;
  EXPECT_EQ(recorded["instructions"]["frames"], 3) << recorded["instructions"];
  EXPECT_EQ(recorded["instructions"]["warmup"], 1) << recorded["instructions"];
  EXPECT_GT(recorded["instructions"]["per_frame"].get<double>(), 0);
  // Not an instruction baseline: its frames are not the run's.
  r = run_cli("check --metric instructions --baseline '" + base + "' -q");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("a timed baseline's work witness, counted over 3 frames"), std::string::npos) << r.err;

  // More instructions: the build's slowdown, failed without measuring again.
  json more = recorded;
  scale_runs(more, "calibrated", 1e-4);
  more["instructions"]["per_frame"] = recorded["instructions"]["per_frame"].get<double>() / 1.2;
  r = run_cli(run + "--baseline '" + write_json(dir / "more.json", more) + "'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("instructions per frame +20.0%: beyond the 7.0% tolerance, the build's own slowdown: not "
                       "measured again"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("measuring again to confirm"), std::string::npos) << r.err;

  // A median far beyond the tolerance that the test cannot call (the
  // baseline's runs in two groups: five far faster than this build, three far
  // slower): more instructions fail it, the same pass.
  json split = recorded;
  json& medians = split["runs"]["median_ms"]["calibrated"];
  ASSERT_EQ(medians.size(), 8u);
  for (size_t i = 0; i < medians.size(); ++i) medians[i] = medians[i].get<double>() * (i < 5 ? 1e-4 : 1e4);
  split["instructions"]["per_frame"] = recorded["instructions"]["per_frame"].get<double>() / 1.2;
  const std::string loud = "check --spread 0 --confirm-spread 0 --runs 8 ";
  r = run_cli(loud + "--baseline '" + write_json(dir / "split.json", split) + "'");
  EXPECT_EQ(r.status, 1) << r.err << r.out;
  EXPECT_NE(r.err.find("not significant): counting this build's instructions"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("instructions per frame +20.0%: beyond the 7.0% tolerance"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("REGRESSION calibrated"), std::string::npos) << r.out;
  split["instructions"]["per_frame"] = recorded["instructions"]["per_frame"];
  r = run_cli(loud + "--baseline '" + write_json(dir / "split.json", split) + "'");
  EXPECT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("but not significant"), std::string::npos) << r.out;

  // The same instructions, and the probe 100 times as fast at the baseline:
  // the machine changed, and the confirmed slowdown is a warning, exit 0.
  json moved = recorded;
  scale_runs(moved, "calibrated", 1e-4);
  for (json& v : moved["samples"]["probe_ms"]) v = v.get<double>() * 0.01;
  const std::string junit = (dir / "moved.xml").string();
  r = run_cli("check --spread 0 --confirm-spread 0 --runs 8 --baseline '" + write_json(dir / "moved.json", moved) +
              "' --junit '" + junit + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("instructions per frame +0.0%: the same work"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("measuring again to confirm"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("crowdprof: warning: slower than the baseline (calibrated +"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the calibration probe, whose work never changes, ran"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("check --against BASE_BINARY"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("WARNING, slower calibrated"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the same work, on a machine that was not as it was for the baseline"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("a warning, the same instructions per frame"), std::string::npos) << r.out;
  const std::string xml = crowdprof::test::read_file(junit);
  EXPECT_NE(xml.find("failures=\"0\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("slower, a warning"), std::string::npos) << xml;
  EXPECT_NE(xml.find("time the change with check --against"), std::string::npos) << xml;
  // Not confirmed (--confirm 0), the same slowdown is no warning: it fails.
  r = run_cli(run + "--confirm 0 --baseline '" + (dir / "moved.json").string() + "'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.find("warning: slower"), std::string::npos) << r.err;

  // --count-work off: no count, and a check against it keeps the timed verdict.
  const std::string plain = (dir / "plain.json").string();
  r = run_cli(run + "'" + humanoid_glb() + "' -n 6 --frames 8 --warmup 1 --baseline '" + plain +
              "' --update-baseline --count-work off");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(read_json(plain).contains("instructions"));
}

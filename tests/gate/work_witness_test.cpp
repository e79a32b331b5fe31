// The work witness's verdict (gate/work_witness.h): more instructions fail,
// the same instructions on a machine seen to have changed warn, the same
// instructions with nothing seen fail; and the meter of other processes' CPU
// time sees a busy neighbour.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "gate/work_witness.h"
#include "measuring/other_load.h"

using crowdprof::decide_witness;
using crowdprof::OtherLoad;
using crowdprof::OtherLoadMeter;
using crowdprof::WorkWitness;

namespace {

WorkWitness counted(double base, double current) {
  WorkWitness w;
  w.base = base;
  w.current = current;
  w.frames = 3;
  w.origin = "callgrind (SIMD AVX2, GNU 12.2.0, 1 thread)";
  return w;
}

OtherLoad neighbour(double cores) {
  OtherLoad load;
  load.known = true;
  load.wall_s = 3;
  load.others_cores = cores;
  load.cores = 2;
  return load;
}

}  // namespace

TEST(WorkWitness, MoreInstructionsAreTheBuildsSlowdownWhateverTheMachine) {
  WorkWitness w = counted(25'000'000, 30'000'000);
  w.load = neighbour(1.0);
  decide_witness(w);
  EXPECT_NEAR(w.change, 0.2, 1e-12);
  EXPECT_EQ(w.verdict, WorkWitness::Verdict::MoreWork);
  EXPECT_FALSE(w.excuses());
  EXPECT_NE(w.line().find("25,000,000 -> 30,000,000 (+20.0%"), std::string::npos) << w.line();
  EXPECT_NE(w.line().find("more work per frame, beyond the 7.0% tolerance: the slowdown is the build's"),
            std::string::npos)
      << w.line();
  w.runs_differ = true;  // --timings-only: the runs need not be of one scene
  EXPECT_NE(w.line().find("the runs differ (--timings-only)"), std::string::npos) << w.line();
}

TEST(WorkWitness, OtherWorkWithinTheToleranceLeavesTheTimedVerdictAlone) {
  // Fewer instructions, or a little more: neither the build's whole slowdown
  // nor a moment of the machine, so neither fails at once nor is excused.
  for (double current : {23'000'000.0, 25'500'000.0}) {
    WorkWitness w = counted(25'000'000, current);
    w.load = neighbour(1.0);
    decide_witness(w);
    EXPECT_EQ(w.verdict, WorkWitness::Verdict::OtherWork) << current;
    EXPECT_FALSE(w.excuses());
    EXPECT_NE(w.line().find("the timed verdict stands"), std::string::npos) << w.line();
  }
}

TEST(WorkWitness, TheSameInstructionsBesideANeighbourAreAWarningThatNamesIt) {
  WorkWitness w = counted(25'000'000, 25'100'000);  // +0.4%: within the count's 1%
  w.load = neighbour(0.98);
  decide_witness(w);
  EXPECT_EQ(w.verdict, WorkWitness::Verdict::MachineMoved);
  EXPECT_TRUE(w.excuses());
  EXPECT_EQ(w.machine(), "other processes took 0.98 of 2 cores during the runs");
  EXPECT_NE(w.line().find("the same work, on a machine that was not as it was for the baseline (other processes"),
            std::string::npos)
      << w.line();
}

TEST(WorkWitness, TheProbesOwnTimeOrStealSayTheMachineChanged) {
  WorkWitness w = counted(25'000'000, 25'000'000);
  w.probe_known = true;
  w.probe_change = 0.12;
  decide_witness(w);
  EXPECT_EQ(w.verdict, WorkWitness::Verdict::MachineMoved);
  EXPECT_EQ(w.machine(),
            "the calibration probe, whose work never changes, ran 12% slower than when the baseline was recorded");
  WorkWitness stolen = counted(25'000'000, 25'000'000);
  stolen.load = neighbour(0);
  stolen.load.steal_cores = 0.5;
  decide_witness(stolen);
  EXPECT_EQ(stolen.verdict, WorkWitness::Verdict::MachineMoved);
  EXPECT_EQ(stolen.machine(), "the hypervisor gave 0.50 cores to other guests (steal)");
  // Other processes and steal count together against a quarter of a core.
  WorkWitness both = counted(25'000'000, 25'000'000);
  both.load = neighbour(0.13);
  both.load.steal_cores = 0.12;
  decide_witness(both);
  EXPECT_EQ(both.verdict, WorkWitness::Verdict::MachineMoved);
  EXPECT_EQ(both.machine(),
            "other processes took 0.13 of 2 cores during the runs; the hypervisor gave 0.12 cores to other guests "
            "(steal)");
}

TEST(WorkWitness, OnlyCpuMetricsCanBeExcused) {
  EXPECT_TRUE(crowdprof::cpu_timed_metric("calibrated"));
  EXPECT_TRUE(crowdprof::cpu_timed_metric("Animations"));
  EXPECT_FALSE(crowdprof::cpu_timed_metric("GPU Latency"));
  EXPECT_FALSE(crowdprof::cpu_timed_metric("gpu"));
}

TEST(WorkWitness, TheSameInstructionsOnTheSameMachineStillFail) {
  // A slowdown the count does not see (memory, threads) on a machine that
  // looks as it did: nothing excuses it.
  WorkWitness w = counted(25'000'000, 25'000'000);
  w.load = neighbour(0.1);
  w.probe_known = true;
  w.probe_change = 0.02;
  decide_witness(w);
  EXPECT_EQ(w.verdict, WorkWitness::Verdict::SameMachine);
  EXPECT_FALSE(w.excuses());
  EXPECT_EQ(w.machine(), "");
  // Nothing known of the machine is not a changed machine.
  WorkWitness unknown = counted(25'000'000, 25'000'000);
  decide_witness(unknown);
  EXPECT_EQ(unknown.verdict, WorkWitness::Verdict::SameMachine);
}

TEST(OtherLoad, ABusyProcessBesideThisOneIsSeen) {
  OtherLoadMeter meter;
  // A process that is not this one's child: the shell backgrounds a busy loop
  // and exits at once, so its CPU time is nobody's here.
  ASSERT_EQ(std::system("timeout 0.8 sh -c 'while :; do :; done' >/dev/null 2>&1 &"), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  OtherLoad load = meter.read();
  if (!load.known) GTEST_SKIP() << "no /proc/stat here";
  EXPECT_GE(load.wall_s, 0.6);
  EXPECT_GE(load.others_cores, 0.4) << "a busy loop ran for most of the window";
  EXPECT_LE(load.others_cores, static_cast<double>(load.cores));
}

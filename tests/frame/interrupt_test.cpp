// ^C during a run: the frames measured so far are reported and written as a
// partial result, the command exits 130, check records no baseline from it; a
// second signal ends the process at once.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "frame/interrupt.h"
#include "test_support.h"

using crowdprof::test::humanoid_glb;
using crowdprof::test::read_file;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Interrupted {
  int status = -1;  // exit status, or -signal when killed by one
  std::string out, err;
};

// Runs crowdprof with `args`, sends `signal_number` once `wait` has passed,
// and waits for it to end.
Interrupted interrupt_cli(const std::vector<std::string>& args, const fs::path& dir, int signal_number,
                          std::chrono::milliseconds wait) {
  pid_t child = fork();
  if (child == 0) {
    int out = open((dir / "out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int err = open((dir / "err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(err, 2);
    std::vector<char*> argv = {const_cast<char*>(CROWDPROF_CLI)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(CROWDPROF_CLI, argv.data());
    _exit(127);
  }
  std::this_thread::sleep_for(wait);
  kill(child, signal_number);
  int raw = 0;
  waitpid(child, &raw, 0);
  Interrupted r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -WTERMSIG(raw);
  r.out = read_file(dir / "out");
  r.err = read_file(dir / "err");
  return r;
}

}  // namespace

TEST(Interrupt, BenchWritesWhatItMeasuredAndExits130) {
  auto dir = crowdprof::test::scratch_dir("interrupt_bench");
  std::string result = (dir / "r.json").string(), csv = (dir / "r.csv").string();
  for (int signal_number : {SIGINT, SIGTERM}) {
    Interrupted r = interrupt_cli(
        {"bench", humanoid_glb(), "-n", "8", "--frames", "10000000", "--warmup", "0", "--json", result, "--csv", csv},
        dir, signal_number, std::chrono::milliseconds(2500));
    ASSERT_EQ(r.status, 130) << r.err;
    EXPECT_NE(r.out.find("Frametime :"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\npartial: interrupted after "), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("crowdprof: interrupted: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("written as a partial result"), std::string::npos) << r.err;
    json j = json::parse(std::ifstream(result));
    EXPECT_TRUE(j["partial"].get<bool>());
    EXPECT_EQ(j["frames_planned"], 10000000);
    size_t frames = j["frames"].get<size_t>();
    EXPECT_GT(frames, 0u);
    EXPECT_LT(frames, 10000000u);
    EXPECT_EQ(j["samples"]["frame_ms"].size(), frames);
    std::string rows = read_file(csv);
    EXPECT_EQ(static_cast<size_t>(std::count(rows.begin(), rows.end(), '\n')), frames + 1);  // and the header
  }
}

TEST(Interrupt, BenchLeavesAnExistingSceneOutAsItWas) {
  auto dir = crowdprof::test::scratch_dir("interrupt_scene_out");
  std::string scene = (dir / "tuned.json").string();
  std::ofstream(scene) << "the earlier scene";
  Interrupted r =
      interrupt_cli({"bench", humanoid_glb(), "-n", "8", "--frames", "10000000", "--warmup", "0", "--scene-out", scene},
                    dir, SIGINT, std::chrono::milliseconds(1500));
  ASSERT_EQ(r.status, 130) << r.err;
  EXPECT_NE(r.err.find("--scene-out " + scene + " is not written from a cut run"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(scene), "the earlier scene");
}

TEST(Interrupt, WithoutOutputFilesNothingClaimsToBeWritten) {
  auto dir = crowdprof::test::scratch_dir("interrupt_no_outputs");
  Interrupted r = interrupt_cli({"bench", humanoid_glb(), "-n", "8", "--frames", "10000000", "--warmup", "0"}, dir,
                                SIGINT, std::chrono::milliseconds(1500));
  ASSERT_EQ(r.status, 130) << r.err;
  EXPECT_NE(r.err.find("crowdprof: interrupted: "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("written"), std::string::npos) << "no file was asked for:\n" << r.err;
}

TEST(Interrupt, CheckNeverRecordsABaselineFromAPartialRun) {
  auto dir = crowdprof::test::scratch_dir("interrupt_check");
  std::string base = (dir / "base.json").string();
  const std::string earlier = R"({"crowdprof": {"format": 1}, "the earlier baseline": true})";
  std::ofstream(base) << earlier;
  Interrupted r = interrupt_cli({"check", "--spread", "0", humanoid_glb(), "-n", "8", "--frames", "10000000",
                                 "--warmup", "0", "--baseline", base, "--update-baseline"},
                                dir, SIGINT, std::chrono::milliseconds(2500));
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_NE(r.err.find("the baseline is not updated from a partial run"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(base), earlier);
}

TEST(Interrupt, CheckForwardsTheSignalToItsRunAndWritesWhatItMeasured) {
  // The run is a child process in a group of its own: only check's forwarding
  // can stop it (the signal goes to check alone, as a terminal's ^C would).
  auto dir = crowdprof::test::scratch_dir("interrupt_check_run");
  std::string base = (dir / "base.json").string();
  ASSERT_EQ(
      crowdprof::test::run_cli("check --spread 0 '" + humanoid_glb() +
                               "' -n 2 --frames 5 --warmup 0 --runs 1 --baseline '" + base + "' --update-baseline -q")
          .status,
      0);
  std::string result = (dir / "partial.json").string();
  Interrupted r =
      interrupt_cli({"check", "--spread", "0", "--baseline", base, "--frames", "10000000", "--json", result}, dir,
                    SIGINT, std::chrono::milliseconds(2500));
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_NE(r.err.find("crowdprof: interrupted: a partial run is not compared"), std::string::npos) << r.err;
  json j = json::parse(std::ifstream(result));
  EXPECT_TRUE(j["partial"].get<bool>());
  EXPECT_GT(j["samples"]["frame_ms"].size(), 0u);
  EXPECT_LT(j["samples"]["frame_ms"].size(), 10000000u);
}

TEST(Interrupt, TheSecondSignalEndsTheProcessAtOnce) {
  pid_t child = fork();
  if (child == 0) {
    install_interrupt_handlers();
    raise(SIGINT);
    if (!interrupt_requested().load()) _exit(3);  // the first only asks
    raise(SIGINT);
    _exit(0);  // not reached: the second ends the process
  }
  int raw = 0;
  waitpid(child, &raw, 0);
  ASSERT_TRUE(WIFSIGNALED(raw)) << "exited with " << WEXITSTATUS(raw);
  EXPECT_EQ(WTERMSIG(raw), SIGINT);
}

TEST(Interrupt, CapacityKeepsTheRoundsBeforeAndMarksTheCutOne) {
  auto dir = crowdprof::test::scratch_dir("interrupt_capacity");
  std::string result = (dir / "c.json").string();
  Interrupted r = interrupt_cli({"capacity", humanoid_glb(), "--budget", "100000", "--modes", "master,threaded",
                                 "--start", "2", "--frames", "10000000", "--warmup", "0", "--json", result},
                                // Long enough for both modes' first blocks under ASan on a busy
                                // 2-core machine, so that each mode has measured a frame.
                                dir, SIGINT, std::chrono::milliseconds(6000));
  ASSERT_EQ(r.status, 130) << r.err;
  EXPECT_NE(r.err.find("crowdprof: interrupted: round 1 was cut short"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("\nmaster "), std::string::npos) << r.out;
  // stdout does not read as an answer: marked first and last, and no points
  // counted from the round that was cut (it said "points 1" beside 0 rounds).
  EXPECT_EQ(r.out.rfind("INTERRUPTED: partial search, not capacities: round 1 was cut short", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("the table holds the 0 whole rounds before it (points: those measured whole)\n", 0),
            std::string::npos)
      << r.out;
  for (const char* mode : {"\nmaster ", "\nthreaded "}) {
    std::string row = r.out.substr(r.out.find(mode) + 1);
    row = row.substr(0, row.find('\n'));
    EXPECT_EQ(row.substr(row.find_last_of(' ') + 1), "0") << r.out;
  }
  json j = json::parse(std::ifstream(result));
  EXPECT_TRUE(j["partial"].get<bool>());
  ASSERT_EQ(j["modes"].size(), 2u);
  for (const json& mode : j["modes"]) {
    ASSERT_EQ(mode["points"].size(), 1u);
    EXPECT_TRUE(mode["points"][0]["partial"].get<bool>());
    EXPECT_GT(mode["points"][0]["frames"].get<size_t>(), 0u);
    EXPECT_TRUE(mode["largest_fit"].is_null());  // the cut round is left out of the search
  }
}

TEST(Interrupt, AdviseWritesThePartialPlan) {
  auto dir = crowdprof::test::scratch_dir("interrupt_advise");
  std::string result = (dir / "a.json").string();
  Interrupted r = interrupt_cli({"advise", humanoid_glb(), "--budget", "0.001", "-n", "4", "--frames", "10000000",
                                 "--warmup", "0", "--json", result},
                                dir, SIGINT, std::chrono::milliseconds(3000));
  ASSERT_EQ(r.status, 130) << r.err;
  EXPECT_NE(r.err.find("crowdprof: interrupted: the plan holds the 0 whole steps before it, written as a partial plan"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("INTERRUPTED: a partial plan"), std::string::npos) << r.out;
  json j = json::parse(std::ifstream(result));
  EXPECT_TRUE(j["partial"].get<bool>());
  EXPECT_EQ(j["advice"]["outcome"], "interrupted");
  ASSERT_EQ(j["runs"].size(), 2u);  // the start, cut, which is also the final configuration
  EXPECT_GT(j["runs"][0]["frames"].get<size_t>(), 0u);
}

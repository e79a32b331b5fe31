// `check --baseline B` from the outside: it reruns everything B recorded
// (switch overrides, the action, the resolution), and a baseline that is not
// a file, records a run no crowdprof makes, or is of another run exits 3
// naming it; a comparison never overwrites its baseline.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "test_support.h"

using crowdprof::test::humanoid_glb;
using crowdprof::test::read_json;
using crowdprof::test::run_cli;
using crowdprof::test::write_json;
using nlohmann::json;

namespace {

// A baseline of a run far from every default: string lookups in the threaded
// preset, one thread, the second action, a square frame (so another aspect
// and so other copies culled).
std::string unusual_baseline(const std::filesystem::path& dir) {
  std::string base = (dir / "base.json").string();
  auto r = run_cli("bench '" + humanoid_glb() +
                   "' -n 12 --frames 8 --warmup 1 --mode threaded --lookups string --threads 1 "
                   "--action walk --resolution 600x600 --fps 30 -q --json '" +
                   base + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  return base;
}

TEST(CheckBaseline, RerunsEverythingTheBaselineRecorded) {
  auto dir = crowdprof::test::scratch_dir("check_baseline_rerun");
  std::string base = unusual_baseline(dir);
  json recorded = read_json(base);
  EXPECT_EQ(recorded["mode"], "threaded+custom");
  EXPECT_EQ(recorded["scene"]["action"], "walk");
  EXPECT_EQ(recorded["scene"]["resolution"], "600x600");

  std::string current = (dir / "current.json").string();
  auto r = run_cli("check --spread 0 --baseline '" + base + "' --tolerance 900% --json '" + current + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.out.rfind("ok cpu", 0), 0u) << r.out;
  json rerun = read_json(current);
  for (const char* key : {"mode", "switches", "threads", "frames", "warmup", "fps", "digest", "counters"})
    EXPECT_EQ(rerun[key], recorded[key]) << key;
  EXPECT_EQ(rerun["scene"], recorded["scene"]);

  // An option on the command line wins, and a different run is refused.
  r = run_cli("check --spread 0 --baseline '" + base + "' --resolution 1600x900 -q");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("the baseline is of another run: resolution \"600x600\" there, \"1600x900\" here"),
            std::string::npos)
      << r.err;
  // A mode given brings its own switches rather than the baseline's overrides.
  r = run_cli("check --spread 0 --baseline '" + base + "' --mode threaded -q");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("mode \"threaded+custom\" there, \"threaded\" here"), std::string::npos) << r.err;
}

// A switch at its plain value is left out of a result, yet the preset may
// hold another (mode shared with share off): the re-run is what ran.
TEST(CheckBaseline, RerunsASwitchTurnedBackToItsPlainValue) {
  auto dir = crowdprof::test::scratch_dir("check_plain_switch");
  auto base = dir / "base.json", run = dir / "run.json";
  auto made = run_cli("bench '" + humanoid_glb() +
                      "' -n 10 --mode shared --share off --frames 4 --warmup 0 -q --json '" + base.string() + "'");
  ASSERT_EQ(made.status, 0) << made.err;
  ASSERT_EQ(read_json(base)["mode"], "shared+custom");
  auto r =
      run_cli("check --spread 0 --baseline '" + base.string() + "' --tolerance 1000% --json '" + run.string() + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("counters and digest match"), std::string::npos) << r.out;
  EXPECT_EQ(read_json(run)["mode"], "shared+custom");
  EXPECT_EQ(read_json(run)["switches"], read_json(base)["switches"]);
}

TEST(CheckBaseline, ValuesNoRunCouldRecordAreTheBaselinesFault) {
  auto dir = crowdprof::test::scratch_dir("check_baseline_corrupt");
  json good = read_json(unusual_baseline(dir));
  struct Corruption {
    const char* name;
    json::json_pointer where;
    json value;
    const char* words;
  };
  const Corruption corruptions[] = {
      {"threads", json::json_pointer("/threads"), json(18446744073709551615ull), "threads '18446744073709551615'"},
      {"fps", json::json_pointer("/fps"), json(-5.0), "fps '-5'"},
      {"camera", json::json_pointer("/scene/camera"), json("somewhere"), "camera 'somewhere'"},
      {"backend", json::json_pointer("/environment/backend"), json("vulkan"), "backend 'vulkan'"},
      {"switch", json::json_pointer("/switches/culling"), json(7), "culling '7'"},
      {"mode", json::json_pointer("/mode"), json("turbo"), "mode 'turbo'"},
  };
  for (const Corruption& c : corruptions) {
    json bad = good;
    bad[c.where] = c.value;
    std::string path = write_json(dir / (std::string(c.name) + ".json"), bad);
    auto r = run_cli("check --spread 0 --baseline '" + path + "' -q");
    EXPECT_EQ(r.status, 3) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.rfind("crowdprof: " + path + ": records a run that crowdprof cannot make: " + c.words, 0), 0u)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  json moonwalk = good;
  moonwalk["scene"]["action"] = "moonwalk";
  std::string path = write_json(dir / "action.json", moonwalk);
  auto r = run_cli("check --spread 0 --baseline '" + path + "' -q");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find(path + ": the baseline is of another run: its action 'moonwalk' is not one of"),
            std::string::npos)
      << r.err;
}

TEST(CheckBaseline, DrawingOrNotIsAnotherRun) {
  auto dir = crowdprof::test::scratch_dir("check_baseline_backend");
  std::string base = unusual_baseline(dir);
  json drawn = read_json(base);
  drawn["environment"]["backend"] = "egl";
  std::string egl = write_json(dir / "egl.json", drawn);
  auto r = run_cli("check --result '" + base + "' --baseline '" + egl + "'");
  EXPECT_EQ(r.status, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("backend \"egl\" there, \"none\" here"), std::string::npos) << r.err;
  // Which GL draws is only noted: the work is the same.
  json osmesa = drawn;
  osmesa["environment"]["backend"] = "osmesa";
  r = run_cli("check --result '" + write_json(dir / "osmesa.json", osmesa) + "' --baseline '" + egl + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.err.find("note: timings may not compare: backend"), std::string::npos) << r.err;
}

TEST(CheckBaseline, OnlyARegularFileIsABaseline) {
  auto dir = crowdprof::test::scratch_dir("check_baseline_files");
  std::string base = unusual_baseline(dir);
  auto r = run_cli("check --result '" + base + "' --baseline '" + dir.string() + "'");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(r.err, "crowdprof: " + dir.string() + ": a directory, not a crowdprof result\n");
  if (std::filesystem::is_character_file("/dev/zero")) {  // would never end if read
    r = run_cli("check --result /dev/zero --baseline '" + base + "'");
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(r.err, "crowdprof: /dev/zero: not a regular file, so not a crowdprof result\n");
  }
}

TEST(CheckBaseline, AComparisonNeverOverwritesItsBaseline) {
  auto dir = crowdprof::test::scratch_dir("check_baseline_overwrite");
  std::string base = unusual_baseline(dir);
  std::string before = read_json(base).dump();
  auto r = run_cli("check --spread 0 --baseline '" + base + "' --json '" + base + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("is the baseline; to replace it, use --update-baseline"), std::string::npos) << r.err;
  EXPECT_EQ(read_json(base).dump(), before);
  // Outputs that cannot be written are found before the run, not after it.
  r = run_cli("check --spread 0 --baseline '" + base + "' --svg '" + (dir / "no" / "chart.svg").string() + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("cannot write SVG file"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// --update-baseline replaces a crowdprof result it cannot read (an older
// format, a cut run), never a user's other file at a mistyped path.
TEST(CheckBaseline, UpdatingReplacesOnlyCrowdprofsOwnFile) {
  auto dir = crowdprof::test::scratch_dir("check_baseline_replace");
  const std::string notes = (dir / "NOTES.md").string(), old = (dir / "old.json").string();
  std::ofstream(notes) << "# my notes\n";
  std::ofstream(dir / "other.json") << R"({"name": "not crowdprof's"})";
  std::ofstream(old) << R"({"crowdprof": {"format": 1, "version": "0.0.1"}})";
  const std::string run = "check --spread 0 --runs 2 --count-work off '" + humanoid_glb() + "' -n 2 --frames 2 ";
  for (const std::string& path : {notes, (dir / "other.json").string()}) {
    const std::string before = crowdprof::test::read_file(path);
    auto r = run_cli(run + "--baseline '" + path + "' --update-baseline");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("refusing to replace --baseline " + path + ": not a crowdprof result"), std::string::npos)
        << r.err;
    EXPECT_EQ(crowdprof::test::read_file(path), before);
  }
  auto r = run_cli(run + "--baseline '" + old + "' --update-baseline");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("note: replacing a baseline that cannot be read"), std::string::npos) << r.err;
  EXPECT_TRUE(read_json(old).contains("samples"));
  // From a --result too; another command's result is not a baseline to replace.
  const std::string diff = (dir / "diff.json").string();
  ASSERT_EQ(run_cli("diff '" + old + "' '" + old + "' -q --json '" + diff + "'").status, 0);
  for (const std::string& path : {notes, diff}) {
    const std::string before = crowdprof::test::read_file(path);
    r = run_cli("check --result '" + old + "' --baseline '" + path + "' --update-baseline");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("refusing to replace --baseline " + path), std::string::npos) << r.err;
    EXPECT_EQ(crowdprof::test::read_file(path), before);
  }
  // An empty file (or only blanks), or a device, written in place, is taken.
  std::ofstream(dir / "blank.json") << "  \n";
  r = run_cli("check --result '" + old + "' --baseline '" + (dir / "blank.json").string() + "' --update-baseline");
  EXPECT_EQ(r.status, 0) << r.err;
  r = run_cli("check --result '" + old + "' --baseline /dev/null --update-baseline");
  EXPECT_EQ(r.status, 0) << r.err;
}

}  // namespace

// A timed failure with the same work is measured again before it fails
// (--confirm, issue 25 item 3): a baseline a hundred times faster than any run
// fails twice, and says so; --confirm 0 fails at once; a result read from a
// file is never measured again.
TEST(CheckBaseline, ATimedFailureIsConfirmedBeforeItFails) {
  auto dir = crowdprof::test::scratch_dir("check_confirm");
  std::string base = (dir / "base.json").string();
  // No work witness: this is the timed confirmation alone (work_witness_cli_test.cpp).
  auto r = run_cli("check --spread 0 '" + humanoid_glb() + "' -n 6 --frames 8 --warmup 1 --runs 2 --baseline '" + base +
                   "' --update-baseline --count-work off -q");
  ASSERT_EQ(r.status, 0) << r.err;
  json fast = read_json(base);
  for (const char* key : {"cpu_ms", "frame_ms"})
    for (json& v : fast["samples"][key]) v = v.get<double>() * 0.01;
  fast.erase("runs");
  std::string fast_base = write_json(dir / "fast.json", fast);
  r = run_cli("check --spread 0 --confirm-spread 0 --baseline '" + fast_base + "' --runs 2 -q");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("with the same work: measuring again to confirm (1 of 1, --confirm)"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("confirmed: slower again (calibrated +"), std::string::npos) << r.err;
  r = run_cli("check --spread 0 --baseline '" + fast_base + "' --runs 2 --confirm 0 -q");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.find("measuring again"), std::string::npos) << r.err;
  r = run_cli("check --baseline '" + fast_base + "' --result '" + base + "' -q");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.find("measuring again"), std::string::npos) << r.err;
  // Other work is never measured again: it is not a slow moment.
  json more = read_json(base);
  more["counters"]["vertices_skinned"] = more["counters"]["vertices_skinned"].get<uint64_t>() + 1;
  r = run_cli("check --spread 0 --confirm-spread 0 --baseline '" + write_json(dir / "more.json", more) +
              "' --runs 2 -q");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.find("measuring again"), std::string::npos) << r.err;
}

// Defects that fuzzing and sanitizer runs found (issue 16), each pinned: numbers
// too large for a double, a Draco attribute of another type than its accessor,
// output lost to a full stdout, a large file read whole before its format is
// looked at, and a trace that grows without bound.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "draco_fixture.h"
#include "gltf_fixture.h"
#include "loader_checks.h"
#include "measuring/trace.h"
#include "skinning/skinning.h"
#include "test_support.h"

namespace crowdprof::test {
namespace {

namespace fs = std::filesystem;

// `text` with its one occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Runs a shell command line (the CLI with redirections or limits run_cli
// cannot express); returns the exit status and what stderr received.
CliResult run_shell(const std::string& command, const fs::path& dir) {
  std::string line = "( " + command + " ) 2>'" + (dir / "stderr").string() + "' </dev/null";
  int raw = std::system(line.c_str());
  CliResult result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.err = read_file(dir / "stderr");
  return result;
}

std::string cli() {
  return std::string("'") + CROWDPROF_CLI + "'";
}

// A small bench result to compare against.
std::string bench_result(const fs::path& dir) {
  std::string character = (dir / "character.glb").string();
  SkinnedFixture().write_glb(character);
  std::string result = (dir / "result.json").string();
  CliResult r =
      run_cli("bench " + crowdprof::test::shell_quoted(character) +
              " -n 2 --frames 3 --warmup 0 --backend none -q --json " + crowdprof::test::shell_quoted(result));
  EXPECT_EQ(r.status, 0) << r.err;
  return result;
}

TEST(HostileInput, ANumberTooLargeForADoubleInACharacterIsABadFile) {
  fs::path dir = scratch_dir("overflow_character");
  std::string minimal = (dir / "minimal.gltf").string();
  write_file(minimal, R"({"asset":{"version":"2.0"},"x":1e400})");
  expect_bad_input(minimal, {"a number too large for a double", "1e400"});
  // Deep inside a real character's GLB JSON chunk, and negative.
  SkinnedFixture fixture;
  fixture.json["nodes"][1]["translation"] = {0, 7777777, 0};
  std::string glb = (dir / "deep.glb").string();
  fixture.write_glb(glb);
  write_file(glb, replaced(read_file(glb), "7777777", "-2e308 "));  // same length: the GLB header stays right
  expect_bad_input(glb, {"a number too large for a double"});
}

TEST(HostileInput, ANumberTooLargeForADoubleInABaselineOrResultIsABadFile) {
  fs::path dir = scratch_dir("overflow_result");
  std::string good = bench_result(dir);
  std::string bad = (dir / "bad.json").string();
  write_file(bad, replaced(read_file(good), "{", "{\"fps\": 1e400, "));
  CliResult r = run_cli("check --baseline " + crowdprof::test::shell_quoted(bad) + " --result " +
                        crowdprof::test::shell_quoted(good));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(r.err.rfind("crowdprof: " + bad + ": a number too large for a double: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = run_cli("check --baseline " + crowdprof::test::shell_quoted(good) + " --result " +
              crowdprof::test::shell_quoted(bad));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(r.err.rfind("crowdprof: " + bad + ": a number too large for a double: ", 0), 0u) << r.err;
}

TEST(HostileInput, ADracoAttributeOfAnotherTypeThanItsAccessorIsRefused) {
  fs::path dir = scratch_dir("draco_type");
  DracoFixture fixture;
  auto& attributes =
      fixture.json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"];
  // WEIGHTS_0 (a float accessor) mapped to Draco's 16-bit JOINTS_0 data: the
  // same four components, so only the type tells them apart.
  attributes["WEIGHTS_0"] = attributes["JOINTS_0"];
  std::string file = (dir / "swapped.glb").string();
  fixture.write_glb(file);
  expect_bad_input(file, {"Draco attribute WEIGHTS_0 holds unsigned 16-bit integers", "component type 5126"});
  // The unmodified fixture still loads.
  std::string good = (dir / "good.glb").string();
  DracoFixture().write_glb(good);
  EXPECT_EQ(load_gltf(good).characters.size(), 1u);
}

TEST(HostileInput, AFailedWriteToStdoutIsAnError) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  fs::path dir = scratch_dir("stdout_full");
  std::string character = (dir / "character.glb").string();
  SkinnedFixture().write_glb(character);
  CliResult r = run_shell(cli() + " info " + crowdprof::test::shell_quoted(character) + " >/dev/full", dir);
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_EQ(r.err, "crowdprof: cannot write to stdout: No space left on device\n");
  // Nothing printed, nothing to lose: still 0.
  r = run_shell(cli() + " info " + crowdprof::test::shell_quoted(character) + " >/dev/null", dir);
  EXPECT_EQ(r.status, 0) << r.err;
}

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define CROWDPROF_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define CROWDPROF_SANITIZED 1
#endif
#endif

TEST(HostileInput, AFileIsJudgedByItsFirstBytesBeforeItIsReadWhole) {
#ifdef CROWDPROF_SANITIZED
  GTEST_SKIP() << "a sanitizer's shadow memory does not run under ulimit -v";
#else
  // 900 MB that are not glTF (sparse: no disk is used), read with 600 MB of
  // address space: reading it whole would run out of memory (exit 4) before
  // the first bytes were judged.
  fs::path dir = scratch_dir("judged_first");
  for (const char* name : {"big.glb", "big.json"}) {
    std::string big = (dir / name).string();
    write_file(big, "\x89PNG\r\n\x1a\n");
    fs::resize_file(big, 900'000'000);
  }
  std::string good = bench_result(dir);
  const std::string limit = "ulimit -v 600000; ";
  CliResult r = run_shell(
      limit + cli() + " info " + crowdprof::test::shell_quoted((dir / "big.glb").string()) + " >/dev/null", dir);
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(r.err,
            "crowdprof: " + (dir / "big.glb").string() + ": is not a glTF file (neither GLB nor a JSON object)\n");
  r = run_shell(limit + cli() + " check -q --baseline " + crowdprof::test::shell_quoted((dir / "big.json").string()) +
                    " --result " + crowdprof::test::shell_quoted(good),
                dir);
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(r.err, "crowdprof: " + (dir / "big.json").string() + ": not a crowdprof result (not a JSON object)\n");
#endif
}

TEST(HostileInput, ATraceKeepsAtMostItsLimitAndSaysWhatItDropped) {
  Tracer tracer(5);
  auto now = Tracer::Clock::now();
  for (int i = 0; i < 8; ++i) tracer.span("work", "stage", now, now, 1);
  EXPECT_EQ(tracer.spans().size(), 5u);
  EXPECT_EQ(tracer.dropped(), 3u);
  std::ostringstream out;
  tracer.write(out);
  nlohmann::json doc = nlohmann::json::parse(out.str());
  EXPECT_EQ(doc["crowdprof"]["dropped_spans"], 3);
  EXPECT_EQ(doc["crowdprof"]["max_spans"], 5);
  EXPECT_EQ(doc, tracer.to_json());
  // A trace within its limit says nothing of the kind.
  Tracer small(5);
  small.span("work", "stage", now, now, 1);
  EXPECT_FALSE(small.to_json().contains("crowdprof"));
}

TEST(HostileInput, ATraceThatWillPassItsLimitIsWarnedAboutBeforeTheRun) {
  EXPECT_TRUE(trace_length_warning(1000, kMaxTraceSpans).empty());
  // 100,000 frames (the 1.7 GB trace of the issue) pass a million spans.
  std::string warning = trace_length_warning(100'000, kMaxTraceSpans).str();
  EXPECT_NE(warning.find("trace keeps 1000000 spans, about the first 90909 of these 100000 frames"), std::string::npos)
      << warning;
}

TEST(HostileInput, ASkinBoundToNoMeshSkinsNothing) {
  // The fuzzer's first find (tests/fuzz/regressions/gltf_loader/skin_without_mesh.glb):
  // a skin whose node lost its mesh loads with no vertices, and skinning its
  // empty range read the joints through a null data() (UBSan: member access
  // within null pointer).
  SkinnedMesh empty;
  SkinningPlan plan;
  ASSERT_EQ("", build_skinning_plan(empty, 3, &plan));
  EXPECT_EQ(0u, plan.batch_count());
  std::vector<SkinMatrix> palette(3, SkinMatrix(1.0f));
  EXPECT_TRUE((SkinningJob{palette, &plan, 0, 0, {}, {}}.Validate()));
  EXPECT_TRUE((SkinningJob{palette, &plan, 0, 0, {}, {}}.Run()));
  EXPECT_FALSE((SkinningJob{palette, &plan, 0, 1, {}, {}}.Validate()));
  Character character =
      load_gltf((source_dir() / "tests/fuzz/regressions/gltf_loader/skin_without_mesh.glb").string()).characters.at(0);
  EXPECT_EQ(character.mesh.vertex_count(), 0u);
  EXPECT_EQ(character.skeleton.joint_count(), 3u);
}

}  // namespace
}  // namespace crowdprof::test

// Smaller mistakes a newcomer makes (issue 27, item 8), each answered with
// what to do: another 3D format (how to get glTF), a result given as a scene
// (which command reads it), and `report` saying where the page went.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "test_support.h"

using crowdprof::test::humanoid_glb;
using crowdprof::test::run_cli;
using crowdprof::test::shell_quoted;
namespace fs = std::filesystem;

TEST(CliGuidance, OtherFormatsAreRefusedWithHowToConvert) {
  auto dir = crowdprof::test::scratch_dir("guidance_formats");
  std::ofstream(dir / "cube.obj") << "# Blender OBJ\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "hero.fbx") << "Kaydara FBX Binary  ";
  for (const char* file : {"cube.obj", "hero.fbx"}) {
    auto r = run_cli("bench " + shell_quoted(dir / file));
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not glTF"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("File > Export > glTF 2.0"), std::string::npos) << r.err;
  }
}

TEST(CliGuidance, AResultGivenAsASceneSaysWhichCommandReadsIt) {
  auto dir = crowdprof::test::scratch_dir("guidance_result");
  fs::path result = dir / "run.json";
  ASSERT_EQ(
      run_cli("bench " + shell_quoted(humanoid_glb()) + " -n 2 --frames 2 --warmup 0 -q --json " + shell_quoted(result))
          .status,
      0);
  auto r = run_cli("bench " + shell_quoted(result));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("run.json: this is a crowdprof result, not a scene file: use report, or check --result"),
            std::string::npos)
      << r.err;
}

TEST(CliGuidance, ReportSaysWhereItWrote) {
  auto dir = crowdprof::test::scratch_dir("guidance_report");
  fs::path result = dir / "run.json", page = dir / "run.html";
  ASSERT_EQ(
      run_cli("bench " + shell_quoted(humanoid_glb()) + " -n 2 --frames 2 --warmup 0 -q --json " + shell_quoted(result))
          .status,
      0);
  auto r = run_cli("report " + shell_quoted(result) + " -o " + shell_quoted(page));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "wrote " + page.string() + ": 1 result\n");
  EXPECT_TRUE(fs::exists(page));
}

TEST(CliGuidance, SummaryCsvHasOneRowPerRun) {
  auto dir = crowdprof::test::scratch_dir("guidance_summary");
  fs::path bench = dir / "bench.csv", compare = dir / "compare.csv";
  ASSERT_EQ(run_cli("bench " + shell_quoted(humanoid_glb()) + " -n 2 --frames 3 --warmup 0 -q --summary-csv " +
                    shell_quoted(bench))
                .status,
            0);
  std::ifstream in(bench);
  std::string header, row, extra;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(header,
            "mode,characters,threads,frames,frame_median_ms,frame_p95_ms,frame_p99_ms,frame_fps,"
            "cpu_median_ms,cpu_p95_ms,cpu_p99_ms,cpu_fps,partial,passes,index_order,"
            "colour_invocations_per_vertex,prepass_invocations_per_vertex,shadows_invocations_per_vertex,"
            "palette_bytes_per_copy_on_screen,record_bytes_per_copy_on_screen");
  EXPECT_EQ(row.rfind("threaded,2,", 0), 0u) << row;
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), std::count(header.begin(), header.end(), ',')) << row;
  EXPECT_FALSE(std::getline(in, extra)) << "one row for one run";
  auto r = run_cli("compare " + shell_quoted(humanoid_glb()) +
                   " --modes master,culled -n 2 --frames 2 --warmup 0 --block 1 -q "
                   "--summary-csv " +
                   shell_quoted(compare));
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream rows(compare);
  std::vector<std::string> lines;
  for (std::string line; std::getline(rows, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[1].rfind("master,2,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("culled,2,", 0), 0u) << lines[2];
}

// --help lists options under headings (issue 24 item 2, issue 27 item 3): the
// settings by the group their table gives, every switch under Mode switches,
// the files written under Outputs, check's gate under Gate and each of its
// two modes under its own heading.
TEST(CliGuidance, HelpGroupsOptionsUnderHeadings) {
  auto under = [](const std::string& help, const std::string& heading, const std::string& option) {
    size_t at = help.find("\n" + heading + ":\n");
    if (at == std::string::npos) return false;
    size_t end = help.find("\n\n", at + heading.size() + 3);
    size_t found = help.find("  " + option + " ", at);
    return found != std::string::npos && found < end;
  };
  auto bench = run_cli("bench --help");
  ASSERT_EQ(bench.status, 0) << bench.err;
  EXPECT_TRUE(under(bench.out, "Crowd", "-n,--characters")) << bench.out;
  EXPECT_TRUE(under(bench.out, "Run", "--mode")) << bench.out;
  EXPECT_TRUE(under(bench.out, "Drawing", "--backend")) << bench.out;
  EXPECT_TRUE(under(bench.out, "Drawing", "--camera")) << bench.out;
  for (const char* option : {"--culling", "--skinning", "--share", "--anim-budget"})
    EXPECT_TRUE(under(bench.out, "Mode switches", option)) << option;
  for (const char* option : {"--json", "--html", "--csv"}) EXPECT_TRUE(under(bench.out, "Outputs", option)) << option;
  auto check = run_cli("check --help");
  ASSERT_EQ(check.status, 0) << check.err;
  for (const char* option : {"--tolerance", "--metric"}) EXPECT_TRUE(under(check.out, "Gate", option)) << option;
  EXPECT_TRUE(under(check.out, "Stored baseline", "--baseline")) << check.out;
  EXPECT_TRUE(under(check.out, "A/B of two builds", "--against")) << check.out;
  EXPECT_TRUE(under(check.out, "Outputs", "--junit")) << check.out;
}

// One style in every --help (issue 27 item 3): values named by what they are,
// defaults as "(default: X)" after the text, never CLI11's INT=10 or
// "INT:INT in [0 - 10]".
TEST(CliGuidance, HelpHasOneStyleOfValuesAndDefaults) {
  for (const char* command : {"info", "gen", "bench", "compare", "capacity", "check", "diff", "render", "report"}) {
    auto r = run_cli(std::string(command) + " --help");
    ASSERT_EQ(r.status, 0) << command << ": " << r.err;
    for (const char* raw : {" INT", " UINT", " FLOAT", " TEXT", ":INT", ":UINT", ":FLOAT", ":TEXT", "=[", " in ["})
      EXPECT_EQ(r.out.find(raw), std::string::npos) << command << " --help shows '" << raw << "':\n" << r.out;
    for (size_t at = r.out.find("\n  -"); at != std::string::npos; at = r.out.find("\n  -", at + 1)) {
      std::string head = r.out.substr(at, r.out.find("  ", at + 4) - at);  // the option and its value name
      EXPECT_EQ(head.find('='), std::string::npos) << command << ": " << head;
    }
  }
  auto check = run_cli("check --help");
  EXPECT_NE(check.out.find("--groups N "), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("(default: 20)"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("--baseline FILE"), std::string::npos) << check.out;
}

// Command-line mistakes get one line that says what to do (issue 27, item 2):
// the nearest command or option for a typo, the option's own words for a value
// that is not a number, what to give when the file is missing, and the
// command's own --help; global options anywhere; lists that never swallow the
// file after them.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "test_support.h"

using crowdprof::test::run_cli;

namespace {

std::string character() {
  std::string path = (crowdprof::test::source_dir() / "scenes" / "humanoid.glb").string();
  return "'" + path + "'";
}

// Exit 2, one line on stderr holding every one of `words`, nothing on stdout.
void expect_usage(const std::string& args, std::initializer_list<const char*> words) {
  auto r = run_cli(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("crowdprof: ", 0), 0u) << r.err;
  for (const char* w : words) EXPECT_NE(r.err.find(w), std::string::npos) << args << ": no '" << w << "' in\n" << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

}  // namespace

TEST(CliErrors, AnUnknownCommandNamesTheNearestAndTheList) {
  expect_usage("bnech " + character(), {"unknown command 'bnech'; did you mean bench?",
                                        "info, gen, bench, compare, capacity, advise, check, diff"});
  expect_usage("--simd SCALAR comapre x.glb", {"unknown command 'comapre'; did you mean compare?"});
  expect_usage("frobnicate", {"unknown command 'frobnicate'", "commands: info, gen, bench"});
  expect_usage("", {"no command given", "commands: info"});
}

TEST(CliErrors, HelpAndVersionAreUnderstood) {
  auto r = run_cli("help");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("bench"), std::string::npos) << r.out;
  r = run_cli("help bench");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("--frames"), std::string::npos) << "bench's own help:\n" << r.out;
  r = run_cli("-v");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("crowdprof 0.", 0), 0u) << r.out;
}

TEST(CliErrors, AnUnknownOptionNamesTheNearestAndTheCommandsHelp) {
  expect_usage("bench " + character() + " --frame 10",
               {"bench: unknown option --frame; did you mean --frames?", "(see crowdprof bench --help)"});
  expect_usage("compare " + character() + " --mode master", {"did you mean --modes?", "see crowdprof compare --help"});
  expect_usage("bench " + character() + " --frobnicate", {"unknown option --frobnicate", "see crowdprof bench --help"});
  expect_usage("info " + character() + " extra.glb",
               {"info: unexpected argument 'extra.glb'", "see crowdprof info --help"});
}

TEST(CliErrors, ANumberThatIsNotOneIsNamedInWords) {
  expect_usage("bench " + character() + " -n abc",
               {"bench: -n/--characters 'abc': expected a whole number", "see crowdprof bench --help"});
  expect_usage("bench " + character() + " --fps fast", {"--fps 'fast': expected a number"});
  expect_usage("capacity " + character() + " --budget abc", {"--budget 'abc': expected a number of milliseconds"});
  expect_usage("gen -o x.glb --seed -1", {"gen: --seed '-1': expected a whole number, 0 or more"});
}

TEST(CliErrors, AFadeLongerThanHalfTheIntervalNamesBothValues) {
  expect_usage(
      "bench " + character() + " --transitions 0.4",
      {"--blend-in 0.25 s (the default) is more than half of --transitions 0.4 s", "give --blend-in 0.2 s or less"});
  expect_usage("bench " + character() + " --transitions 0.5 --blend-in 0.3",
               {"--blend-in 0.3 s is more than half of --transitions 0.5 s"});
}

TEST(CliErrors, AValueLeftOutOrGivenTwiceIsSaidSo) {
  expect_usage("bench " + character() + " --frames", {"bench: --frames needs a value (--frames N)"});
  expect_usage("bench " + character() + " --frames 2 --frames 3",
               {"bench: --frames was given more than once; it takes one value"});
}

TEST(CliErrors, AMissingFileSaysWhatToGive) {
  expect_usage("bench", {"bench: no file given: name a character (.glb or .gltf) or a scene file (.json)",
                         "see crowdprof bench --help"});
  expect_usage("report x.json", {"report: -o/--output is required", "see crowdprof report --help"});
}

TEST(CliErrors, GlobalOptionsAreTakenAnywhereAndBadValuesRefused) {
  auto r = run_cli("bench " + character() + " -n 2 --frames 2 --warmup 0 -q --simd SSE4 --stores regular");
  EXPECT_EQ(r.status, 0) << r.err;
  r = run_cli("--simd SSE4 --version");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("SIMD SSE4"), std::string::npos) << r.out;
  expect_usage("--simd AVX9 --version", {"SIMD target \"AVX9\""});
  expect_usage("--version --simd AVX9", {"SIMD target \"AVX9\""});
  expect_usage("--stores fast --version", {"unknown store policy \"fast\""});
  expect_usage("bench " + character() + " --simd AVX9", {"SIMD target \"AVX9\""});
}

TEST(CliErrors, AListOptionTakesOneValueAndLeavesTheFile) {
  // The file after --modes is the file, not a mode.
  auto r = run_cli("compare --modes master,culled " + character() + " -n 2 --frames 2 --warmup 0 --block 1");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("culled"), std::string::npos) << r.out;
  r = run_cli("capacity --modes master " + character() +
              " --budget 1000 --start 1 --max-characters 2 --frames 2 "
              "--warmup 0 -q");
  EXPECT_EQ(r.status, 0) << r.err;
}

// Every command's --help ends with an example of that command (the man pages'
// EXAMPLES sections are made from it), and the top level's with one too.
#include <string>

#include <gtest/gtest.h>

#include "test_support.h"

namespace {

// The last non-empty line of `text`.
std::string last_line(const std::string& text) {
  size_t end = text.find_last_not_of('\n');
  if (end == std::string::npos) return "";
  size_t start = text.rfind('\n', end);
  start = start == std::string::npos ? 0 : start + 1;
  return text.substr(start, end - start + 1);
}

}  // namespace

TEST(HelpExamples, EveryCommandsHelpEndsWithAnExampleOfIt) {
  for (std::string command : {"info", "gen", "bench", "compare", "capacity", "check", "diff", "render", "report"}) {
    auto r = crowdprof::test::run_cli(command + " --help");
    ASSERT_EQ(r.status, 0) << command << ": " << r.err;
    EXPECT_NE(r.out.find("\nExamples:\n  crowdprof " + command + " "), std::string::npos) << r.out;
    EXPECT_EQ(last_line(r.out).rfind("  crowdprof " + command + " ", 0), 0u) << command << ": " << last_line(r.out);
  }
  auto top = crowdprof::test::run_cli("--help");
  ASSERT_EQ(top.status, 0) << top.err;
  EXPECT_EQ(last_line(top.out), "  crowdprof bench scenes/thesis.json");
}

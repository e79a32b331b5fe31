// Every --help reads as one document (issue 55 item 4): what the command does,
// its arguments, its options under headings that each hold several (the
// required ones first), one blank line between sections; and the texts a
// newcomer tripped over say what they mean.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

using crowdprof::test::run_cli;

namespace {

const std::vector<std::string> kCommands = {"info",  "gen",  "bench",  "compare", "capacity",
                                            "check", "diff", "render", "report"};

struct Section {
  std::string heading;
  std::vector<std::string> options;  // each option's first line, as printed
};

// The sections of a --help between "Usage:" and "Examples:", in order.
std::vector<Section> sections_of(const std::string& help) {
  std::vector<Section> out;
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) {
    if (line == "Examples:") break;
    if (!line.empty() && line.back() == ':' && line.front() != ' ')
      out.push_back({line.substr(0, line.size() - 1), {}});
    else if (!out.empty() && line.rfind("  ", 0) == 0 && line.size() > 2 && line[2] != ' ')
      out.back().options.push_back(line.substr(2));
  }
  return out;
}

// The section that lists `option` ("--calibrate"), or "".
std::string heading_of(const std::vector<Section>& sections, const std::string& option) {
  for (const Section& s : sections)
    for (const std::string& line : s.options)
      if (line.rfind(option + " ", 0) == 0 || line.find("," + option + " ") != std::string::npos || line == option)
        return s.heading;
  return "";
}

}  // namespace

TEST(HelpText, EveryCommandReadsAsOneDocument) {
  for (const std::string& command : kCommands) {
    auto r = run_cli(command + " --help");
    ASSERT_EQ(r.status, 0) << command << ": " << r.err;
    // The description first, then the usage after one blank line.
    EXPECT_NE(r.out.find("\n\nUsage: crowdprof " + command + " "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("\n\n\n"), std::string::npos) << command << " has a double blank line:\n" << r.out;
    std::vector<Section> sections = sections_of(r.out);
    ASSERT_FALSE(sections.empty()) << r.out;
    for (const Section& s : sections) {
      // No heading of -h alone, nor any other heading of one option.
      if (s.heading != "Arguments")
        EXPECT_GE(s.options.size(), 2u) << command << ": '" << s.heading << "' holds " << s.options.size() << ":\n"
                                        << r.out;
      EXPECT_NE(s.heading, "Options") << command << ": a heading that says nothing:\n" << r.out;
    }
    // Defaults as a reader reads them: no 0.03333333333333333.
    std::smatch long_number;
    EXPECT_FALSE(std::regex_search(r.out, long_number, std::regex("[0-9]\\.[0-9]{5,}")))
        << command << ": " << long_number.str();
    // No CLI11 set spelling such as "VALUE:{default,locomotion}".
    EXPECT_EQ(r.out.find(":{"), std::string::npos) << command << ":\n" << r.out;
    EXPECT_EQ(heading_of(sections, "--help"), "General") << r.out;
    EXPECT_EQ(heading_of(sections, "--simd"), "General") << command << ": the global options are a command's too";
  }
  auto top = run_cli("--help");
  ASSERT_EQ(top.status, 0) << top.err;
  EXPECT_EQ(top.out.find("\n\n\n"), std::string::npos) << top.out;
}

// A required option opens the first heading: capacity's --budget sat last.
TEST(HelpText, RequiredOptionsComeFirst) {
  const std::map<std::string, std::string> required = {
      {"capacity", "--budget"}, {"gen", "-o,--output"}, {"render", "-o,--output"}, {"report", "-o,--output"}};
  for (const auto& [command, option] : required) {
    auto r = run_cli(command + " --help");
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<Section> sections = sections_of(r.out);
    size_t first = sections.front().heading == "Arguments" ? 1 : 0;
    ASSERT_GT(sections.size(), first) << r.out;
    ASSERT_FALSE(sections[first].options.empty()) << r.out;
    EXPECT_EQ(sections[first].options.front().rfind(option + " ", 0), 0u) << command << ":\n" << r.out;
    EXPECT_NE(sections[first].options.front().find("(required)"), std::string::npos) << r.out;
  }
}

TEST(HelpText, OptionsSitUnderTheirMeaning) {
  auto bench = run_cli("bench --help");
  ASSERT_EQ(bench.status, 0) << bench.err;
  std::vector<Section> sections = sections_of(bench.out);
  // What a frame records is measurement, not a file written.
  for (const char* option : {"--calibrate", "--count-instructions", "--frames", "--warmup"})
    EXPECT_EQ(heading_of(sections, option), "Measurement") << option << "\n" << bench.out;
  for (const char* option : {"--json", "--csv", "--html", "--quiet"})
    EXPECT_EQ(heading_of(sections, option), "Outputs") << option;
  // A fraction of a second as a reader reads it.
  EXPECT_NE(bench.out.find("0.0333 in budget"), std::string::npos) << bench.out;
  EXPECT_EQ(bench.out.find("0.03333"), std::string::npos) << bench.out;
  // A file an output declaration writes is a FILE in every command, diff's too.
  for (const std::string& command : kCommands) {
    auto r = run_cli(command + " --help");
    for (const char* output : {"--json ", "--html ", "--csv ", "--svg ", "--junit ", "-o,--output "}) {
      size_t at = r.out.find("\n  " + std::string(output));
      if (at == std::string::npos || (command == "info" && std::string(output) == "--json ")) continue;
      EXPECT_EQ(r.out.substr(at + 3 + std::string(output).size(), 4), "FILE") << command << " " << output;
    }
  }
}

// check's two modes have two sets of defaults, and its help says both.
TEST(HelpText, CheckSaysBothModesDefaultsAndWhatProbesAre) {
  auto r = run_cli("check --help");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("(default: 7%; with --against, 5%)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(default: calibrated; with --against, frame)"), std::string::npos) << r.out;
  std::string summary = r.out.substr(0, r.out.find("\n\nUsage:"));
  std::replace(summary.begin(), summary.end(), '\n', ' ');  // a paragraph wrapped at 100 columns
  EXPECT_NE(summary.find("--baseline"), std::string::npos) << summary;
  EXPECT_NE(summary.find("--against"), std::string::npos) << summary;
  // The calibrated unit, explained where it is named.
  EXPECT_NE(summary.find("in probes: 0.45 probes is a frame that took 0.45 times as long as its probe"),
            std::string::npos)
      << summary;
  std::vector<Section> sections = sections_of(r.out);
  EXPECT_EQ(heading_of(sections, "--baseline"), "Stored baseline");
  EXPECT_EQ(heading_of(sections, "--against"), "A/B of two builds");
  EXPECT_EQ(heading_of(sections, "--tolerance"), "Gate");
  // The top level lists each command by its first sentence.
  auto top = run_cli("--help");
  size_t at = top.out.find("\n  check ");
  ASSERT_NE(at, std::string::npos) << top.out;
  std::string line = top.out.substr(at + 1, top.out.find('\n', at + 1) - at - 1);
  EXPECT_NE(line.find("--against"), std::string::npos) << line;
  EXPECT_EQ(line.find("defaults"), std::string::npos) << line;
}

TEST(HelpText, ReportNamesEveryResultItReads) {
  auto r = run_cli("report --help");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("bench, check, compare, capacity or advise --json"), std::string::npos) << r.out;
}

// gen's bounds are named as the command and option the user typed.
TEST(HelpText, GenNamesItsCommandAndOption) {
  for (const auto& [args, said] : std::vector<std::pair<std::string, std::string>>{
           {"--bones 10", "crowdprof: gen: --bones '10': expected 20 to 1024 (see crowdprof gen --help)\n"},
           {"--vertices 3", "crowdprof: gen: --vertices '3': expected 500 to 2500000 (see crowdprof gen --help)\n"},
           {"--lods 4", "crowdprof: gen: --lods '4': expected 0 to 3 (see crowdprof gen --help)\n"}}) {
    auto dir = crowdprof::test::scratch_dir("help_text_gen");
    auto r = run_cli("gen " + args + " -o " + crowdprof::test::shell_quoted(dir / "x.glb"));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err, said);
  }
}

// docs/errors.md quotes what the binary prints (issue 27 item 3): each command
// below makes one of the lines it quotes, and the line must be in the doc as
// printed. A message changed in the code without the doc fails here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "test_support.h"

namespace {

using crowdprof::test::run_cli;

std::string read_doc() {
  std::ifstream in(crowdprof::test::source_dir() / "docs" / "errors.md");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string first_line(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

std::string quoted_path(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += "'";
  return text;
}

struct Quoted {
  std::string args;  // after the binary; HUMANOID is the default character
  int status;
  // The doc quotes the line up to here when the rest depends on the machine ("" : all of it).
  std::string machine_part = "";
};

TEST(ErrorsDoc, QuotesWhatTheBinaryPrints) {
  const std::string doc = read_doc();
  ASSERT_FALSE(doc.empty());
  const std::string humanoid = quoted_path(crowdprof::test::source_dir() / "scenes" / "humanoid.glb");
  const std::string missing = quoted_path(crowdprof::test::scratch_dir("errors_doc") / "none.json");
  const Quoted quoted[] = {
      {"bnech x", 2},
      {"bench --frame 3 HUMANOID", 2},
      {"bench -n abc HUMANOID", 2},
      {"bench", 2},
      {"report r.json", 2},
      {"info HUMANOID extra.glb", 2},
      {"bench -n 0 HUMANOID", 2},
      {"bench --mode fast HUMANOID", 2},
      {"bench --threads 0 HUMANOID", 2},
      {"bench --backend vulkan HUMANOID", 2},
      {"bench --resolution 0x10 HUMANOID", 2},
      {"bench --mode hwskin HUMANOID", 2},
      {"gen --bones 10 -o never-written.glb", 2},
      {"check HUMANOID --baseline MISSING --tolerance ten", 2},
      {"check HUMANOID --baseline MISSING --metric fps", 2},
      {"compare HUMANOID --modes bogus", 2},
      {"capacity HUMANOID --budget 0", 2},
      {"capacity HUMANOID --budget 2 --precision 1", 2},
      {"capacity HUMANOID --budget 2 --start 30 --max-characters 20", 2},
      {"--stores fast bench HUMANOID", 2},
      {"--simd AVX9 bench HUMANOID", 2, " (choose from"},
  };
  for (const Quoted& q : quoted) {
    std::string args = q.args;
    for (auto [name, value] : {std::pair<std::string, std::string>{"HUMANOID", humanoid}, {"MISSING", missing}})
      if (size_t at = args.find(name); at != std::string::npos) args.replace(at, name.size(), value);
    auto r = run_cli(args);
    EXPECT_EQ(r.status, q.status) << q.args << ": " << r.err;
    std::string line = first_line(r.err);
    if (!q.machine_part.empty()) line = line.substr(0, line.find(q.machine_part));
    ASSERT_FALSE(line.empty()) << q.args;
    EXPECT_NE(doc.find(line), std::string::npos)
        << "docs/errors.md does not quote what `crowdprof " << q.args << "` prints:\n"
        << line;
  }
}

}  // namespace

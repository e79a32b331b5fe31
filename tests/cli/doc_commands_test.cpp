// Every crowdprof command quoted in README.md and docs/ still parses: the
// options it names exist and take the values it gives them (issue 26 item 5).
// Parsed only (CROWDPROF_PARSE_ONLY), not run: the values' meaning and the
// files they name are other tests' business (docs/pipeline.md's are run).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace crowdprof::test {
namespace {

namespace fs = std::filesystem;

struct Quoted {
  std::string file, line;
};

// Lines of fenced blocks that call crowdprof, continuation lines joined.
std::vector<Quoted> quoted_commands() {
  std::vector<fs::path> files = {source_dir() / "README.md"};
  for (const auto& entry : fs::directory_iterator(source_dir() / "docs"))
    if (entry.path().extension() == ".md") files.push_back(entry.path());
  std::vector<Quoted> out;
  for (const fs::path& file : files) {
    std::ifstream in(file);
    std::string line, pending;
    bool inside = false;
    while (std::getline(in, line)) {
      if (line.rfind("```", 0) == 0) {
        inside = !inside;
        continue;
      }
      if (!inside) continue;
      line = line.substr(std::min(line.find_first_not_of(' '), line.size()));
      if (line.rfind("$ ", 0) == 0) line = line.substr(2);
      line = pending + line;
      pending.clear();
      if (!line.empty() && line.back() == '\\') {
        pending = line.substr(0, line.size() - 1);
        continue;
      }
      for (const char* prefix : {"crowdprof ", "build/crowdprof ", "./build/crowdprof "})
        if (line.rfind(prefix, 0) == 0) {
          out.push_back({file.filename().string(), line.substr(std::string(prefix).size())});
          break;
        }
    }
  }
  return out;
}

// The arguments alone: up to a pipe, a redirection, a comment or the next
// command; a synopsis's [optional] parts taken, and of a|b the first.
std::string arguments_of(std::string line) {
  for (const char* end : {" | ", " || ", " > ", " >> ", " 2>", " < ", " && ", " ; ", " #"})
    if (size_t at = line.find(end); at != std::string::npos) line = line.substr(0, at);
  std::istringstream words(line);
  std::string word, args;
  while (words >> word) {
    std::erase(word, '[');
    std::erase(word, ']');
    if (size_t bar = word.find('|'); bar != std::string::npos) word = word.substr(0, bar);
    if (!word.empty()) args += (args.empty() ? "" : " ") + word;
  }
  return args;
}

TEST(DocCommands, EveryQuotedCommandStillParses) {
  const fs::path dir = scratch_dir("doc_commands");
  std::vector<Quoted> commands = quoted_commands();
  EXPECT_GE(commands.size(), 40u);  // found them, not none
  for (const Quoted& quoted : commands) {
    const std::string command = "cd '" + dir.string() + "' && CROWDPROF_PARSE_ONLY=1 '" + CROWDPROF_CLI + "' " +
                                arguments_of(quoted.line) + " >out 2>err </dev/null";
    const int raw = std::system(command.c_str());
    std::ifstream err_file(dir / "err");
    std::string err((std::istreambuf_iterator<char>(err_file)), std::istreambuf_iterator<char>());
    // A target this CPU lacks (--simd AVX3 on a machine without AVX-512) is
    // refused by name: the command parsed, the machine cannot run it.
    const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    if (err.find("\" is not supported by this CPU (choose from") != std::string::npos) {
      EXPECT_EQ(2, status) << quoted.file << ": crowdprof " << quoted.line;
      continue;
    }
    EXPECT_EQ(status, 0) << quoted.file << ": crowdprof " << quoted.line << "\n" << err;
  }
}

TEST(DocCommands, AnOptionTheBinaryLacksFailsTheParse) {
  // What the test above relies on: the parse alone refuses a misspelled option.
  const std::string command =
      std::string("CROWDPROF_PARSE_ONLY=1 '") + CROWDPROF_CLI + "' bench x.glb --modez threaded >/dev/null 2>&1";
  const int raw = std::system(command.c_str());
  EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 2);
  EXPECT_EQ(arguments_of("check [FILE] --metric frame,Animations|all [--json F] | tee x"),
            "check FILE --metric frame,Animations --json F");
}

}  // namespace
}  // namespace crowdprof::test

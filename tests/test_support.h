// Shared helpers for the tests: where things are, and running the CLI.
#pragma once

#include <filesystem>
#include <string>

namespace crowdprof::test {

inline std::filesystem::path source_dir() { return CROWDPROF_SOURCE_DIR; }
inline std::filesystem::path samples_dir() { return CROWDPROF_SAMPLES_DIR; }
inline bool have_samples() { return std::filesystem::is_directory(samples_dir()); }
inline std::string sample(const std::string& relative) { return (samples_dir() / relative).string(); }

// A fresh, empty folder for one test's files.
std::filesystem::path scratch_dir(const std::string& name);

struct CliResult {
  int status = -1;
  std::string out, err;
};
// Runs the built crowdprof with `args` (shell-quoted by the caller).
CliResult run_cli(const std::string& args);

// True when this machine can make a GL context (the CLI would too).
bool have_gl();

}  // namespace crowdprof::test

#define CROWDPROF_REQUIRE_SAMPLES()                                                                 \
  do {                                                                                            \
    if (!crowdprof::test::have_samples())                                                         \
      GTEST_SKIP() << "sample characters not found at " << crowdprof::test::samples_dir().string() \
                   << " (they sit beside the project, in ../shared/samples)";                    \
  } while (0)

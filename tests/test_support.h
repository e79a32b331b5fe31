// Shared helpers for the tests: where things are, and running the CLI.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <filesystem>
#include <string>

namespace crowdprof::test {

inline std::filesystem::path source_dir() {
  return CROWDPROF_SOURCE_DIR;
}
inline std::filesystem::path samples_dir() {
  return CROWDPROF_SAMPLES_DIR;
}
inline bool have_samples() {
  return std::filesystem::is_directory(samples_dir());
}
inline std::string sample(const std::string& relative) {
  return (samples_dir() / relative).string();
}

// scenes/humanoid.glb, the bundled thesis character, as a path string.
inline std::string humanoid_glb() {
  return (source_dir() / "scenes" / "humanoid.glb").string();
}
// `path` in single quotes, for a shell command line.
inline std::string shell_quoted(const std::string& text) {
  return "'" + text + "'";
}

// A file's bytes ("" when it cannot be read: the test's own checks say why).
std::string read_file(const std::filesystem::path& path);
nlohmann::json read_json(const std::filesystem::path& path);
// Writes `doc` (indented) to `path` and returns the path, to pass on.
std::string write_json(const std::filesystem::path& path, const nlohmann::json& doc);
// How many times `what` occurs in `text`, overlaps counted.
size_t occurrences(const std::string& text, const std::string& what);

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

#define CROWDPROF_REQUIRE_SAMPLES()                                                                \
  do {                                                                                             \
    if (!crowdprof::test::have_samples())                                                          \
      GTEST_SKIP() << "sample characters not found at " << crowdprof::test::samples_dir().string() \
                   << " (they sit beside the project, in ../shared/samples)";                      \
  } while (0)

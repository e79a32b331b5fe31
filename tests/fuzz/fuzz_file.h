// The readers under fuzz take a path, as the CLI gives them: each input is
// written to a file in a private folder first. The folder holds nothing else,
// so a fuzzed URI that names a neighbour finds nothing to read.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace crowdprof::fuzz {

// <private folder>/<name>: where an input is written, or, for a reader that
// takes bytes, the name its messages use and the folder its URIs resolve in.
inline std::string input_path(const char* name) {
  static const std::filesystem::path folder = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "crowdprof-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) std::abort();
    return std::filesystem::path(pattern);
  }();
  return (folder / name).string();
}

// Writes `data` to input_path(name) and returns the path. Aborts when the
// file cannot be written: a fuzz run on a full disk would only find that.
inline std::string write_input(const uint8_t* data, size_t size, const char* name) {
  std::string path = input_path(name);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file || (size && std::fwrite(data, 1, size, file) != size) || std::fclose(file) != 0) std::abort();
  return path;
}

}  // namespace crowdprof::fuzz

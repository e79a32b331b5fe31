#include "test_support.h"

#include "render/gl_context.h"

#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>

namespace crowdprof::test {

std::filesystem::path scratch_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("crowdprof_test_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json read_json(const std::filesystem::path& path) {
  return nlohmann::json::parse(std::ifstream(path));
}

std::string write_json(const std::filesystem::path& path, const nlohmann::json& doc) {
  std::ofstream(path) << doc.dump(1);
  return path.string();
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

CliResult run_cli(const std::string& args) {
  auto dir = scratch_dir("cli");
  std::string command = std::string("'") + CROWDPROF_CLI + "' " + args + " >'" + (dir / "out").string() + "' 2>'" +
                        (dir / "err").string() + "' </dev/null";
  int raw = std::system(command.c_str());
  CliResult result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.out = read_file(dir / "out");
  result.err = read_file(dir / "err");
  return result;
}

bool have_gl() {
  static const bool have = [] {
    try {
      return open_backend(BackendChoice::Auto, nullptr) != nullptr;
    } catch (const std::exception&) {
      return false;
    }
  }();
  return have;
}

}  // namespace crowdprof::test

#include "test_support.h"

#include "render/gl_context.h"

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

static std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliResult run_cli(const std::string& args) {
  auto dir = scratch_dir("cli");
  std::string command = std::string("'") + CROWDPROF_CLI + "' " + args + " >'" + (dir / "out").string() + "' 2>'" +
                        (dir / "err").string() + "' </dev/null";
  int raw = std::system(command.c_str());
  CliResult result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.out = slurp(dir / "out");
  result.err = slurp(dir / "err");
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

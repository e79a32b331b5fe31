#include "cli/installed_data.h"

#include <filesystem>
#include <iostream>
#include <system_error>

namespace fs = std::filesystem;

std::string installed_data_dir() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) return "";
  const fs::path data = self.parent_path().parent_path() / "share" / "crowdprof";
  return fs::is_directory(data / "scenes", error) ? data.string() : "";
}

std::string with_installed_data(const std::string& path) {
  const std::string file = path.substr(0, path.find("#skin="));
  std::error_code error;
  if (file.empty() || fs::path(file).is_absolute() || fs::exists(file, error)) return path;
  const std::string data = installed_data_dir();
  if (data.empty()) return path;
  const fs::path installed = (fs::path(data) / file).lexically_normal();
  if (!fs::is_regular_file(installed, error)) return path;
  std::cerr << "crowdprof: note: " << file << " is not here: using the installed " << installed.string() << "\n";
  return installed.string() + path.substr(file.size());
}

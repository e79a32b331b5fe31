#include "output/output_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "asset/errors.h"

namespace crowdprof {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, const std::string& reason) {
  throw UsageError("cannot write " + what + " file '" + path + "': " + reason);
}

}  // namespace

void require_writable(const std::string& path, const std::string& what) {
  namespace fs = std::filesystem;
  if (path.empty()) fail(path, what, "empty path");
  std::error_code error;
  fs::file_status status = fs::status(path, error);
  if (fs::is_directory(status)) fail(path, what, "it is a directory");
  if (fs::exists(status)) {
    if (access(path.c_str(), W_OK) != 0) fail(path, what, std::strerror(errno));
    return;
  }
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, error)) fail(path, what, "no folder " + folder.string());
  if (access(folder.c_str(), W_OK | X_OK) != 0) fail(path, what, std::strerror(errno));
}

void write_file(const std::string& path, const std::string& what, std::string_view bytes) {
  require_writable(path, what);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) fail(path, what, std::strerror(errno));
  bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  int saved = errno;
  if (std::fclose(file) != 0 && written) written = false, saved = errno;
  if (!written) fail(path, what, std::strerror(saved ? saved : EIO));
}

}  // namespace crowdprof

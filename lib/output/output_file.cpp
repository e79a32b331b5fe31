#include "output/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "asset/errors.h"
#include "asset/gltf_loader.h"

namespace crowdprof {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, const std::string& reason) {
  throw UsageError("cannot write " + what + " file '" + path + "': " + reason);
}

fs::path folder_of(const std::string& path) {
  fs::path folder = fs::path(path).parent_path();
  return folder.empty() ? fs::path(".") : folder;
}

// A new file in `folder` named after `path`, open for writing; its name in
// `temp`. -1 with errno set when the folder cannot take it.
int make_temporary(const fs::path& folder, const std::string& path, std::string& temp) {
  std::string name = ".";
  name += fs::path(path).filename().string();
  name += ".crowdprof-XXXXXX";
  temp = (folder / name).string();
  return mkstemp(temp.data());
}

bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes.remove_prefix(static_cast<size_t>(n));
  }
  return true;
}

// Where a path leads, for comparing: absolute, with "." and ".." resolved and
// symbolic links followed as far as the path exists.
std::string canonical_spelling(const std::string& path) {
  std::error_code error;
  fs::path resolved = fs::weakly_canonical(fs::absolute(path, error), error);
  return error ? fs::absolute(path).lexically_normal().string() : resolved.string();
}

bool same_file(const std::string& a, const std::string& b) {
  if (canonical_spelling(a) == canonical_spelling(b)) return true;
  struct stat sa {}, sb {};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

// Where `path` will be written: false for an existing non-regular file (a
// device, a pipe: written in place); true with a temporary file open in the
// path's folder (`fd`, named `temp`). UsageError for what cannot be written.
bool open_beside(const std::string& path, const std::string& what, int& fd, std::string& temp) {
  if (path.empty()) fail(path, what, "empty path");
  std::error_code error;
  fs::file_status status = fs::status(path, error);
  if (fs::is_directory(status)) fail(path, what, "it is a directory");
  if (fs::exists(status) && !fs::is_regular_file(status)) return false;
  fs::path folder = folder_of(path);
  if (!fs::is_directory(folder, error)) fail(path, what, "no folder " + folder.string());
  fd = make_temporary(folder, path, temp);
  if (fd < 0) fail(path, what, "the folder " + folder.string() + " cannot take a new file: " + std::strerror(errno));
  return true;
}

}  // namespace

void require_writable(const std::string& path, const std::string& what) {
  int fd = -1;
  std::string temp;
  if (open_beside(path, what, fd, temp)) {
    ::close(fd);
    ::unlink(temp.c_str());
  } else if (access(path.c_str(), W_OK) != 0) {  // a device or a pipe: only it must open
    fail(path, what, std::strerror(errno));
  }
}

void write_file(const std::string& path, const std::string& what, std::string_view bytes) {
  int fd = -1;
  std::string temp;
  if (!open_beside(path, what, fd, temp)) {
    fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) fail(path, what, std::strerror(errno));
    bool written = write_all(fd, bytes);
    int saved = errno;
    if (::close(fd) != 0 && written) written = false, saved = errno;
    if (!written) fail(path, what, std::strerror(saved ? saved : EIO));
    return;
  }
  // mkstemp makes 0600; a result file gets what a plain open would give it
  // (0666 less the umask), and a replaced file keeps its own mode.
  struct stat old {};
  mode_t mode;
  if (::stat(path.c_str(), &old) == 0) {
    mode = old.st_mode & 07777;
  } else {
    mode_t mask = ::umask(0);
    ::umask(mask);
    mode = 0666 & ~mask;
  }
  bool written = write_all(fd, bytes) && ::fchmod(fd, mode) == 0 && ::fsync(fd) == 0;
  int saved = errno;
  if (::close(fd) != 0 && written) written = false, saved = errno;
  if (written && ::rename(temp.c_str(), path.c_str()) != 0) written = false, saved = errno;
  if (!written) {
    ::unlink(temp.c_str());
    fail(path, what, std::strerror(saved ? saved : EIO));
  }
}

void require_distinct_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (size_t o = 0; o < outputs.size(); ++o) {
    const NamedPath& out = outputs[o];
    if (out.path.empty()) continue;
    for (const NamedPath& in : inputs) {
      if (in.path.empty()) continue;
      std::string file = in.path;
      try {
        file = parse_character_spec(in.path).file;
      } catch (const UsageError&) {
      }
      if (same_file(out.path, file))
        throw UsageError(out.option + " " + out.path + " is the " + in.option +
                         "; refusing to overwrite an input (choose another output path)");
    }
    for (size_t p = 0; p < o; ++p)
      if (!outputs[p].path.empty() && same_file(out.path, outputs[p].path))
        throw UsageError(outputs[p].option + " and " + out.option + " both write " + out.path +
                         "; give each output its own path");
  }
}

}  // namespace crowdprof

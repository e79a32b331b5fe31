#include "base/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "base/errors.h"
#include "base/input_file.h"

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

// The descriptor of this process that `path` names (/dev/stdout is a link to
// /proc/self/fd/1), or -1. Such a path is a "magic" link: the file behind it
// is what the descriptor has open (a redirection's file, at its offset), so it
// is written through the descriptor, never replaced by name.
int own_descriptor(const std::string& path) {
  if (path == "-") return STDOUT_FILENO;
  std::string pid = "/proc/" + std::to_string(::getpid()) + "/fd/";
  for (const std::string& prefix :
       {std::string("/proc/self/fd/"), std::string("/proc/thread-self/fd/"), std::string("/dev/fd/"), pid}) {
    if (path.size() <= prefix.size() || path.compare(0, prefix.size(), prefix) != 0) continue;
    int fd = -1;
    const char* first = path.data() + prefix.size();
    const char* last = path.data() + path.size();
    auto [end, error] = std::from_chars(first, last, fd);
    if (error == std::errc() && end == last && fd >= 0) return fd;
  }
  return -1;
}

// Where a path given as an output leads: symbolic links followed to the file
// they name (which may not exist yet: a dangling link is written through, as
// a shell's redirection does), or one of this process's descriptors.
struct Destination {
  int descriptor = -1;  // >= 0: write to this open descriptor
  std::string target;   // otherwise: the file written
};

Destination resolve(const std::string& path, const std::string& what) {
  Destination destination;
  std::string current = path;
  for (int hop = 0; hop < 40; ++hop) {
    destination.descriptor = own_descriptor(current);
    if (destination.descriptor >= 0) return destination;
    struct stat status {};
    if (::lstat(current.c_str(), &status) != 0 || !S_ISLNK(status.st_mode)) {
      destination.target = current;
      return destination;
    }
    std::error_code error;
    fs::path link = fs::read_symlink(current, error);
    if (error) fail(path, what, error.message());
    // A relative link is relative to the folder the link sits in.
    current = link.is_absolute() ? link.string() : (fs::path(current).parent_path() / link).string();
  }
  fail(path, what, "too many levels of symbolic links");
}

// How a reason reads when the path led elsewhere through links.
std::string via(const std::string& path, const Destination& destination, const std::string& reason) {
  if (destination.target.empty() || destination.target == path) return reason;
  return reason + " (" + path + " is a link to " + destination.target + ")";
}

// A new file in `folder` named after `target`, open for writing; its name in
// `temp`. -1 with errno set when the folder cannot take it.
int make_temporary(const fs::path& folder, const std::string& target, std::string& temp) {
  std::string name = ".";
  name += fs::path(target).filename().string();
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
// symbolic links followed, a dangling one to the file it would create.
std::string canonical_spelling(const std::string& path) {
  Destination destination;
  try {
    destination = resolve(path, "");
  } catch (const UsageError&) {
    destination.target = path;
  }
  if (destination.descriptor >= 0) return "descriptor " + std::to_string(destination.descriptor);
  std::error_code error;
  fs::path resolved = fs::weakly_canonical(fs::absolute(destination.target, error), error);
  return error ? fs::absolute(destination.target).lexically_normal().string() : resolved.string();
}

bool same_file(const std::string& a, const std::string& b) {
  if (canonical_spelling(a) == canonical_spelling(b)) return true;
  if (a == "-" || b == "-") return false;
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

// How `destination` is written.
enum class Way {
  Descriptor,  // through an open descriptor of this process (-, /dev/stdout)
  InPlace,     // opened and truncated: a device, a pipe, or a file whose folder takes no new file
  Replace,     // a temporary file beside the target, renamed over it (`fd` open, named `temp`)
};

Way choose_way(const std::string& path, const std::string& what, const Destination& destination, int& fd,
               std::string& temp) {
  if (path.empty()) fail(path, what, "empty path");
  if (destination.descriptor >= 0) {
    int flags = ::fcntl(destination.descriptor, F_GETFL);
    if (flags < 0) fail(path, what, "descriptor " + std::to_string(destination.descriptor) + " is not open");
    if ((flags & O_ACCMODE) == O_RDONLY)
      fail(path, what, "descriptor " + std::to_string(destination.descriptor) + " is open for reading only");
    return Way::Descriptor;
  }
  const std::string& target = destination.target;
  struct stat status {};
  bool exists = ::stat(target.c_str(), &status) == 0;
  if (exists && S_ISDIR(status.st_mode)) fail(path, what, via(path, destination, "it is a directory"));
  if (exists && !S_ISREG(status.st_mode)) return Way::InPlace;
  fs::path folder = folder_of(target);
  std::error_code error;
  if (!fs::is_directory(folder, error)) fail(path, what, via(path, destination, "no folder " + folder.string()));
  fd = make_temporary(folder, target, temp);
  if (fd >= 0) return Way::Replace;
  int saved = errno;
  // A file the user may write in a folder that takes no new file (a shared
  // folder, a read-only mount's writable file): written in place.
  if (exists && ::access(target.c_str(), W_OK) == 0) return Way::InPlace;
  fail(path, what,
       via(path, destination, "the folder " + folder.string() + " cannot take a new file: " + std::strerror(saved)));
}

void write_descriptor(const std::string& path, const std::string& what, int descriptor, std::string_view bytes) {
  // What was printed on stdout before comes before this file's bytes.
  std::cout.flush();
  std::fflush(stdout);
  if (descriptor == STDOUT_FILENO) {
    std::cout.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    std::cout.flush();
    if (!std::cout) fail(path, what, "cannot write to stdout");
    return;
  }
  if (!write_all(descriptor, bytes)) fail(path, what, std::strerror(errno ? errno : EIO));
}

void write_in_place(const std::string& path, const std::string& what, const std::string& target,
                    std::string_view bytes) {
  int fd = ::open(target.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) fail(path, what, std::strerror(errno));
  bool written = write_all(fd, bytes);
  int saved = errno;
  if (::close(fd) != 0 && written) written = false, saved = errno;
  if (!written) fail(path, what, std::strerror(saved ? saved : EIO));
}

}  // namespace

void require_writable(const std::string& path, const std::string& what) {
  Destination destination = resolve(path, what);
  int fd = -1;
  std::string temp;
  switch (choose_way(path, what, destination, fd, temp)) {
    case Way::Descriptor:
      break;
    case Way::Replace:
      ::close(fd);
      ::unlink(temp.c_str());
      break;
    case Way::InPlace:  // a device, a pipe or a file: only it must open
      if (::access(destination.target.c_str(), W_OK) != 0) fail(path, what, std::strerror(errno));
      break;
  }
}

void write_file(const std::string& path, const std::string& what, std::string_view bytes) {
  Destination destination = resolve(path, what);
  int fd = -1;
  std::string temp;
  Way way = choose_way(path, what, destination, fd, temp);
  if (way == Way::Descriptor) return write_descriptor(path, what, destination.descriptor, bytes);
  const std::string& target = destination.target;
  if (way == Way::InPlace) return write_in_place(path, what, target, bytes);
  // mkstemp makes 0600, owned by us; a new file gets what a plain open would
  // give it (0666 less the umask), and a replaced file keeps its mode and owner.
  struct stat old {};
  mode_t mode;
  if (::stat(target.c_str(), &old) == 0) {
    mode = old.st_mode & 07777;
    if ((old.st_uid != ::geteuid() || old.st_gid != ::getegid()) && ::fchown(fd, old.st_uid, old.st_gid) != 0) {
      // Not ours to give away: the file is written in place, keeping its owner.
      ::close(fd);
      ::unlink(temp.c_str());
      return write_in_place(path, what, target, bytes);
    }
  } else {
    mode_t mask = ::umask(0);
    ::umask(mask);
    mode = 0666 & ~mask;
  }
  bool written = write_all(fd, bytes) && ::fchmod(fd, mode) == 0 && ::fsync(fd) == 0;
  int saved = errno;
  if (::close(fd) != 0 && written) written = false, saved = errno;
  if (written && ::rename(temp.c_str(), target.c_str()) != 0) written = false, saved = errno;
  if (!written) {
    ::unlink(temp.c_str());
    fail(path, what, std::strerror(saved ? saved : EIO));
  }
}

bool is_standard_output(const std::string& path) {
  if (path.empty()) return false;
  try {
    return resolve(path, "").descriptor == STDOUT_FILENO;
  } catch (const UsageError&) {
    return false;
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

bool prints_on_stdout(bool quiet, std::initializer_list<std::string> outputs) {
  if (quiet) return false;
  for (const std::string& path : outputs)
    if (is_standard_output(path)) return false;
  return true;
}

void write_text(const std::string& path, const std::string& what, const std::function<void(std::ostream&)>& body) {
  std::ostringstream text;
  body(text);
  write_file(path, what, text.view());
}

void OutputFiles::add(std::string option, std::string what, std::string path) {
  files_.push_back({std::move(option), std::move(what), std::move(path)});
}

void OutputFiles::require_usable(const std::vector<NamedPath>& inputs) const {
  std::vector<NamedPath> outputs;
  for (const OutputFile& file : files_) outputs.push_back({file.option, file.path});
  require_distinct_outputs(inputs, outputs);
  for (const OutputFile& file : files_)
    if (!file.path.empty()) require_writable(file.path, file.what);
}

std::string OutputFiles::path(std::string_view option) const {
  for (const OutputFile& file : files_)
    if (file.option == option) return file.path;
  return {};
}

OutputFiles OutputFiles::without(std::initializer_list<std::string_view> options) const {
  OutputFiles kept;
  for (const OutputFile& file : files_)
    if (std::find(options.begin(), options.end(), file.option) == options.end()) kept.files_.push_back(file);
  return kept;
}

bool OutputFiles::prints_on_stdout(bool quiet) const {
  if (quiet) return false;
  for (const OutputFile& file : files_)
    if (is_standard_output(file.path)) return false;
  return true;
}

}  // namespace crowdprof

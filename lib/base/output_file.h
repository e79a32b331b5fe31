// Writing the files a user asked for (results, charts, images, characters),
// with one clear error when a path cannot take them, and never at the cost of a
// file the user already has. An output path is part of the command line, so its
// errors are UsageErrors (exit 2, docs/errors.md).
#pragma once

#include <functional>
#include <initializer_list>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace crowdprof {

// Throws UsageError "cannot write <what> file '<path>': <reason>" when `path`
// is a directory or sits in a folder that is missing or cannot take a new file.
// The folder is tried for real (a temporary file is created and removed there),
// since permission bits say nothing for root or on a read-only mount. Commands
// call it before a long run so the run is not wasted.
void require_writable(const std::string& path, const std::string& what);

// Replaces `path` with `bytes` atomically: written to a temporary file in the
// same folder, flushed, then renamed over `path`, so a failure (a full disk, a
// signal) leaves the earlier file as it was. A symbolic link is followed: the
// file it names is replaced (keeping its mode and owner) or, for a dangling
// link, created; the link stays. "-" is standard output, and so is any path
// that names one of this process's descriptors (/dev/stdout, /dev/fd/N): written
// through the descriptor. A path that is not a regular file (a pipe, a device),
// or a file whose folder takes no new file, is written in place. UsageError as
// above when it cannot be written.
void write_file(const std::string& path, const std::string& what, std::string_view bytes);

// True when writing `path` writes standard output ("-", /dev/stdout, a link
// to it): a command then prints nothing else there, so the file stays whole.
bool is_standard_output(const std::string& path);

// Whether a command prints its text on stdout: not with --quiet, nor when one
// of its output files is stdout ("--csv -", /dev/stdout), which then holds
// that file alone.
bool prints_on_stdout(bool quiet, std::initializer_list<std::string> outputs);

// Writes `path` with `body` (write_file); UsageError naming the file when it cannot.
void write_text(const std::string& path, const std::string& what, const std::function<void(std::ostream&)>& body);

// A file the command reads or writes, named as its option is: {"--json", path}.
struct NamedPath {
  std::string option;
  std::string path;
};

// UsageError, before any work, when an output is one of the inputs (the same
// path, or the same file by device and inode: a link, another spelling; links
// followed, a dangling one to the file it would create) or two outputs share a
// path (also "-" and /dev/stdout): "--json X.glb is the input file; refusing to overwrite
// it". Empty paths are ignored; "FILE#skin=N" inputs are compared as FILE.
void require_distinct_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

// One file a command writes: the option that names it, what it holds (in
// messages: "cannot write SVG file ..."), and its path (empty: not asked for).
struct OutputFile {
  std::string option;
  std::string what;
  std::string path;
};

// A command's output files, each declared once (hyperfine's ExportManager):
// checked together before any work, and asked whether stdout stays free.
class OutputFiles {
 public:
  void add(std::string option, std::string what, std::string path);
  // UsageError, before any work: an output that is one of `inputs` or two that
  // share a path (require_distinct_outputs), then one that cannot be written
  // (require_writable), in the order added.
  void require_usable(const std::vector<NamedPath>& inputs) const;
  // Whether the command prints its text on stdout: not `quiet`, and none of
  // the files is stdout (which then holds that file alone).
  bool prints_on_stdout(bool quiet) const;
  // The path given for `option` ("--json"); empty when it was not declared or not given.
  std::string path(std::string_view option) const;
  // The same files but those of `options`: what a command writes when it
  // leaves some out (check --update-baseline writes no verdict).
  OutputFiles without(std::initializer_list<std::string_view> options) const;
  const std::vector<OutputFile>& files() const { return files_; }

 private:
  std::vector<OutputFile> files_;
};

}  // namespace crowdprof

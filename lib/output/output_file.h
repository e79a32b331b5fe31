// Writing the files a user asked for (results, charts, images, characters),
// with one clear error when a path cannot take them, and never at the cost of a
// file the user already has. An output path is part of the command line, so its
// errors are UsageErrors (exit 2, docs/errors.md).
#pragma once

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
// signal) leaves the earlier file as it was. A path that exists and is not a
// regular file (/dev/stdout, a pipe) is written in place. UsageError as above
// when it cannot be written.
void write_file(const std::string& path, const std::string& what, std::string_view bytes);

// A file the command reads or writes, named as its option is: {"--json", path}.
struct NamedPath {
  std::string option;
  std::string path;
};

// UsageError, before any work, when an output is one of the inputs (the same
// path, or the same file by device and inode: a link, another spelling) or two
// outputs share a path: "--json X.glb is the input file; refusing to overwrite
// it". Empty paths are ignored; "FILE#skin=N" inputs are compared as FILE.
void require_distinct_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace crowdprof

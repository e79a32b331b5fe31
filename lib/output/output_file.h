// Writing the files a user asked for (results, charts, images, characters),
// with one clear error when a path cannot take them. An output path is part of
// the command line, so its errors are UsageErrors (exit 2, docs/errors.md).
#pragma once

#include <string>
#include <string_view>

namespace crowdprof {

// Throws UsageError "cannot write <what> file '<path>': <reason>" when `path`
// is a directory or sits in a folder that is missing or not writable. Touches
// nothing: commands call it before a long run so the run is not wasted.
void require_writable(const std::string& path, const std::string& what);

// Replaces `path` with `bytes`; UsageError as above when it cannot, a full disk
// included.
void write_file(const std::string& path, const std::string& what, std::string_view bytes);

}  // namespace crowdprof

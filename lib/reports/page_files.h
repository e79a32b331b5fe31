// The HTML report's script and style, kept as files in lib/reports/page/ (so
// that they read, diff and lint as JavaScript and CSS) and embedded at build
// time (cmake/embed_files.cmake), so a report is one self-contained file.
#pragma once

#include <span>
#include <string_view>

namespace crowdprof {

struct EmbeddedPageFile {
  std::string_view name;  // its path in the source tree, e.g. "lib/reports/page/report.css"
  std::string_view text;
};

// Every page file. Defined in the generated source.
std::span<const EmbeddedPageFile> embedded_page_files();

// The text of `name`; throws std::logic_error when the build embedded no such
// file (a bug, not bad input).
std::string_view page_file(std::string_view name);

}  // namespace crowdprof

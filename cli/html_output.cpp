#include "cli/html_output.h"

#include <fstream>
#include <iterator>

#include "base/errors.h"
#include "base/modes.h"
#include "base/output_file.h"

void write_html_report(const std::string& path, crowdprof::HtmlReportInput input) {
  crowdprof::write_file(path, "HTML", crowdprof::html_report(input));
}

std::string read_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw crowdprof::InputError(path, "cannot be read");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  crowdprof::require_png(bytes, path);
  return bytes;
}

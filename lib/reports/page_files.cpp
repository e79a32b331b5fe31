#include "reports/page_files.h"

#include <stdexcept>
#include <string>

namespace crowdprof {

std::string_view page_file(std::string_view name) {
  for (const EmbeddedPageFile& file : embedded_page_files())
    if (file.name == name) return file.text;
  throw std::logic_error("no page file '" + std::string(name) + "' was embedded in this build");
}

}  // namespace crowdprof

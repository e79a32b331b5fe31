// Text tables as the commands print them on stdout.
#pragma once

#include <string>
#include <vector>

namespace crowdprof {

// Rows of cells as a text table: columns two spaces apart, right-aligned
// except the columns in `left` (text); no trailing spaces.
std::string align_columns(const std::vector<std::vector<std::string>>& rows, const std::vector<size_t>& left);

}  // namespace crowdprof

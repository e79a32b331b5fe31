#include "base/errors.h"

namespace crowdprof {

namespace {

bool is_name(std::string_view text) {
  if (text.empty()) return false;
  for (char c : text)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

}  // namespace

std::string SettingText::str(const Speller& spell) const {
  std::string out;
  out.reserve(marked_.size());
  for (size_t i = 0; i < marked_.size();) {
    const size_t open = marked_.find('{', i);
    if (open == std::string::npos) {
      out.append(marked_, i);
      break;
    }
    out.append(marked_, i, open - i);
    const size_t close = marked_.find('}', open);
    const std::string_view inside =
        close == std::string::npos ? std::string_view{} : std::string_view(marked_).substr(open + 1, close - open - 1);
    if (!is_name(inside)) {
      out += '{';
      i = open + 1;
      continue;
    }
    out += spell(inside);
    i = close + 1;
  }
  return out;
}

std::string SettingText::str() const {
  return str([](std::string_view name) { return std::string(name); });
}

}  // namespace crowdprof

#include "profile/number_text.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace crowdprof {

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string percent(double fraction) {
  if (!std::isfinite(fraction)) return fraction > 0 ? "+inf%" : "n/a";
  // Appended, not `"+" + string`: GCC 12 warns falsely on that (-Wrestrict, its bug 105329).
  std::string text = fraction >= 0 ? "+" : "";
  text += fixed(fraction * 100.0, 1);
  text += '%';
  return text;
}

std::optional<double> parse_number(std::string_view text) {
  if (text.empty() || text.size() > 32) return std::nullopt;
  std::string copy(text);
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(copy, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != copy.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace crowdprof

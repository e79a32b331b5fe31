#include "base/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

std::string significant(double value, int digits) {
  if (!std::isfinite(value)) return "n/a";
  if (value == 0) return "0";
  const int magnitude = static_cast<int>(std::floor(std::log10(std::fabs(value))));
  const int decimals = std::max(0, digits - 1 - magnitude);
  const double scale = std::pow(10.0, digits - 1 - magnitude);
  const double rounded = std::round(value * scale) / scale;  // 1370.4 at 3 digits: 1370
  return fixed(rounded, decimals);
}

std::string duration_text(double ms) {
  if (!std::isfinite(ms)) return "n/a";
  return ms < 1.0 ? significant(ms * 1000.0, 3) + " µs" : significant(ms, 3) + " ms";
}

std::string p_value_text(double p) {
  char text[32];
  std::snprintf(text, sizeof text, p < 1e-4 ? "%.1e" : "%.4f", p);
  return text;
}

std::string with_thousands(uint64_t count) {
  std::string digits = std::to_string(count), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// The shortest decimal that reads back as `value`.
std::string shortest_text(double value) {
  char text[32];
  if (value == std::floor(value) && std::fabs(value) < 1e15) {
    std::snprintf(text, sizeof text, "%.0f", value);
    return text;
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

}  // namespace crowdprof

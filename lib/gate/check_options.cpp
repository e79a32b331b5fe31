#include "gate/check_options.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "base/errors.h"
#include "measuring/category_clock.h"

namespace crowdprof {

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// A non-negative decimal number that is all of `s` (no sign, no words, finite).
bool parse_plain_number(const std::string& s, double& value) {
  size_t used = 0;
  if (s.empty() || !(std::isdigit(static_cast<unsigned char>(s[0])) || s[0] == '.')) return false;
  try {
    value = std::stod(s, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == s.size() && std::isfinite(value);
}

}  // namespace

double parse_tolerance(std::string_view text) {
  std::string s(text);
  bool is_percent = !s.empty() && s.back() == '%';
  if (is_percent) s.pop_back();
  double value = 0;
  if (!parse_plain_number(s, value))
    throw SettingError("tolerance", std::string(text), "expected a percentage such as 10% or a fraction such as 0.1");
  if (!is_percent && value >= 1)
    throw SettingError("tolerance", std::string(text),
                       "a fraction is below 1; for percent write " + std::string(text) + "%");
  if (is_percent) value /= 100.0;
  if (value > 10.0) throw SettingError("tolerance", std::string(text), "at most 1000%");
  return value;
}

Floor parse_floor(std::string_view text) {
  std::string s(text);
  auto bad = [&](const std::string& why) { return SettingError("floor", std::string(text), why); };
  double scale = 0;  // to ms; 0 for a percentage
  bool is_percent = false;
  for (auto [suffix, to_ms] : {std::pair<const char*, double>{"ms", 1.0}, {"us", 1e-3}, {"s", 1000.0}}) {
    std::string_view sv(s);
    if (sv.size() > std::strlen(suffix) && sv.ends_with(suffix)) {
      s.resize(s.size() - std::strlen(suffix));
      scale = to_ms;
      break;
    }
  }
  if (scale == 0 && !s.empty() && s.back() == '%') {
    s.pop_back();
    is_percent = true;
  }
  const char* expected = "expected a time such as 0.05ms or 50us, or a share of the baseline's median frame such as 2%";
  if (scale == 0 && !is_percent) throw bad(expected);
  double value = 0;
  if (!parse_plain_number(s, value)) throw bad(expected);
  Floor floor;
  if (is_percent) {
    if (value > 1000) throw bad("at most 1000%");
    floor.fraction_of_frame = value / 100.0;
  } else {
    if (value * scale > 3.6e6) throw bad("at most an hour");
    floor.fraction_of_frame = 0;
    floor.ms = value * scale;
  }
  return floor;
}

double floor_ms(const Floor& floor, double frame_ms) {
  return floor.fraction_of_frame > 0 ? floor.fraction_of_frame * frame_ms : floor.ms;
}

std::string metric_display_name(const std::string& key) {
  if (key == "frame_ms") return "frame";
  if (key == "cpu_ms") return "cpu";
  if (key == "calibrated") return "calibrated";
  for (size_t c = 0; c < kCategoryCount; ++c)
    if (key == series_name(static_cast<Category>(c))) return std::string(category_name(static_cast<Category>(c)));
  return key;
}

std::vector<std::string> all_metrics() {
  std::vector<std::string> keys = {"frame_ms"};
  for (size_t c = 0; c < kCategoryCount; ++c) keys.emplace_back(series_name(static_cast<Category>(c)));
  return keys;
}

std::string resolve_metric(std::string_view name) {
  std::string wanted = lower(name);
  if (wanted == "frame" || wanted == "frame_ms") return "frame_ms";
  if (wanted == "cpu" || wanted == "cpu_ms") return "cpu_ms";
  if (wanted == "calibrated") return "calibrated";
  std::string choices = "frame, cpu, calibrated";
  for (size_t c = 0; c < kCategoryCount; ++c) {
    auto category = static_cast<Category>(c);
    if (wanted == lower(category_name(category)) || wanted == category_column(category) ||
        wanted == series_name(category))
      return series_name(category);
    choices += ", " + std::string(category_name(category));
  }
  throw SettingError("metric", std::string(name), "expected one of " + choices);
}

}  // namespace crowdprof

#include "profile/number_text.h"

#include <cmath>
#include <cstdio>

namespace crowdprof {

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string percent(double fraction) {
  if (!std::isfinite(fraction)) return fraction > 0 ? "+inf%" : "n/a";
  return (fraction >= 0 ? "+" : "") + fixed(fraction * 100.0, 1) + "%";
}

}  // namespace crowdprof

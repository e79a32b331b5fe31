// Numbers as text: as the tables print them, and as users type them.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace crowdprof {

// `value` with exactly `decimals` digits after the point ("%.*f").
std::string fixed(double value, int decimals);

// A relative change as a signed percentage with one decimal: 0.071 → "+7.1%";
// +infinity (a change from zero) → "+inf%", NaN → "n/a".
std::string percent(double fraction);

// A finite number that is the whole text ("0.05", "1e3"; not "5ms" or ""),
// else nullopt.
std::optional<double> parse_number(std::string_view text);

}  // namespace crowdprof

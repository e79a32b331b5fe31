// Numbers as text: as the tables print them, and as users type them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace crowdprof {

// `value` with exactly `decimals` digits after the point ("%.*f").
std::string fixed(double value, int decimals);

// A relative change as a signed percentage with one decimal: 0.071 → "+7.1%";
// +infinity (a change from zero) → "+inf%", NaN → "n/a".
std::string percent(double fraction);

// `value` to `digits` significant digits, never in exponent form: 1370.4 ->
// "1370", 0.7314 -> "0.731", 86 -> "86.0".
std::string significant(double value, int digits);

// A duration for a reader: 3 significant digits, in µs below 1 ms
// ("731 µs", "1.01 ms", "16.7 ms").
std::string duration_text(double ms);

// A count with thousands separated by commas: 168334 -> "168,334".
std::string with_thousands(uint64_t count);

// A test's p-value as reports print it: 4 decimals, or "1.2e-05" below 1e-4.
std::string p_value_text(double p);

// The shortest decimal that reads back as `value` ("0.25", "1e-07", "3").
std::string shortest_text(double value);

// A finite number that is the whole text ("0.05", "1e3"; not "5ms" or ""),
// else nullopt.
std::optional<double> parse_number(std::string_view text);

}  // namespace crowdprof

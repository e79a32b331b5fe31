// Numbers as the tables print them.
#pragma once

#include <string>

namespace crowdprof {

// `value` with exactly `decimals` digits after the point ("%.*f").
std::string fixed(double value, int decimals);

// A relative change as a signed percentage with one decimal: 0.071 → "+7.1%";
// +infinity (a change from zero) → "+inf%", NaN → "n/a".
std::string percent(double fraction);

}  // namespace crowdprof

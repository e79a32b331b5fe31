// What compare --sweep varies: the crowd's size, or the draws of the crowd a
// frame (modes.h's passes).
#pragma once

#include <cstdint>
#include <string_view>

namespace crowdprof {

enum class SweepAxis : uint8_t { Characters, Passes };

// "characters" or "passes", as results name the axis (and its sweep rows the key).
inline std::string_view to_string(SweepAxis axis) {
  return axis == SweepAxis::Passes ? "passes" : "characters";
}

}  // namespace crowdprof

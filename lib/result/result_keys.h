// The names a result's JSON uses that its writer (result_writer.cpp) and its
// reader (result_reader.cpp) share. Internal to those two.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "measuring/counters.h"
#include "measuring/gpu_passes.h"

namespace crowdprof::result_keys {

// The counters a result stores per character of the crowd.
inline constexpr std::string_view kCharacterCounters[] = {"copies_visible", "copies_culled", "poses_updated",
                                                          "vertices_skinned", "copies_fallback"};

// The field of counter `name`, or null.
inline const CounterField* counter_field(std::string_view name) {
  for (const CounterField& field : kCounterFields)
    if (field.name == name) return &field;
  return nullptr;
}

// A pass's per-frame GPU times in "samples": gpu_<pass>_ms.
inline std::string pass_samples_key(size_t pass) {
  return "gpu_" + std::string(kGpuPassNames[pass]) + "_ms";
}

}  // namespace crowdprof::result_keys

// The GL backends --backend and a scene file's "backend" name, as words: the
// vocabulary of the setting, parsed where settings are read (frame/run_spec),
// opened where GL lives (render/gl_context.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace crowdprof {

// What --backend names: a backend, `auto` (EGL, then OSMesa, then none) or none.
enum class BackendChoice : uint8_t { Auto, Egl, OsMesa, None };
// Null for anything but auto, egl, osmesa, none.
std::optional<BackendChoice> parse_backend(std::string_view name);

}  // namespace crowdprof

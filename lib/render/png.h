// Writing a frame as a PNG (stb_image_write).
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace crowdprof {

// RGBA8 pixels, rows top to bottom. Throws UsageError naming the path when it
// cannot be written.
void write_png(const std::string& path, int width, int height, std::span<const uint8_t> rgba);

}  // namespace crowdprof

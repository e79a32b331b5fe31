// The only file that compiles stb_image_write's implementation.
#include "render/png.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "asset/errors.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace crowdprof {

void write_png(const std::string& path, int width, int height, std::span<const uint8_t> rgba) {
  if (width < 1 || height < 1 || rgba.size() != static_cast<size_t>(width) * static_cast<size_t>(height) * 4)
    throw std::invalid_argument("write_png: pixels do not match the size");
  errno = 0;
  if (!stbi_write_png(path.c_str(), width, height, 4, rgba.data(), width * 4))
    throw UsageError("cannot write PNG file '" + path + "'" + (errno ? std::string(": ") + std::strerror(errno) : ""));
}

}  // namespace crowdprof

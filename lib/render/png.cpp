// The only file that compiles stb_image_write's implementation.
#include "render/png.h"

#include <stdexcept>

#include "base/output_file.h"

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
  // Encoded in memory, so that a write that fails (a full disk) is seen:
  // stbi_write_png ignores fwrite's result.
  std::string bytes;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, width, height, 4, rgba.data(), width * 4))
    throw std::runtime_error("stb_image_write could not encode a " + std::to_string(width) + "x" +
                             std::to_string(height) + " PNG");
  write_file(path, "PNG", bytes);
}

}  // namespace crowdprof

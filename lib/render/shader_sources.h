// The GLSL sources in shaders/, embedded at build time (cmake/embed_files.cmake) so
// the binary needs no install directory to find them.
#pragma once

#include <span>
#include <string_view>

namespace crowdprof {

struct EmbeddedShader {
  std::string_view name;  // its path in the source tree, e.g. "shaders/lit.frag"
  std::string_view text;
};

// Every shader, in no particular order. Defined in the generated source.
std::span<const EmbeddedShader> embedded_shaders();

// The text of `name` ("shaders/lit.frag"); throws std::logic_error when the
// build embedded no such file (a bug, not bad input).
std::string_view embedded_shader(std::string_view name);

}  // namespace crowdprof

#include "render/shader_sources.h"

#include <stdexcept>
#include <string>

namespace crowdprof {

std::string_view embedded_shader(std::string_view name) {
  for (const EmbeddedShader& shader : embedded_shaders())
    if (shader.name == name) return shader.text;
  throw std::logic_error("no shader '" + std::string(name) + "' was embedded in this build");
}

}  // namespace crowdprof

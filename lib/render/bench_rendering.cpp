#include "render/bench_rendering.h"

namespace crowdprof {

std::string BenchRendering::backend_name() const {
  return context ? std::string(to_string(context->backend())) : "none";
}

std::string BenchRendering::renderer_name() const {
  if (!context) return "none";
  // The vendor names the driver where the renderer names only the chip.
  return context->renderer() + " (" + context->platform() + ", OpenGL " + context->version() + ", GL_VENDOR " +
         context->vendor() + ")";
}

BenchRendering open_rendering(BackendChoice choice, std::span<const Character* const> characters, size_t copies,
                              const RendererConfig& config, SettingText* warning) {
  BenchRendering rendering;
  rendering.context = open_backend(choice, warning);
  if (rendering.context)
    rendering.renderer = std::make_unique<GlCrowdRenderer>(*rendering.context, characters, copies, config);
  return rendering;
}

BenchRendering open_rendering(BackendChoice choice, const Character& character, size_t copies,
                              const RendererConfig& config, SettingText* warning) {
  const Character* one[] = {&character};
  return open_rendering(choice, one, copies, config, warning);
}

}  // namespace crowdprof

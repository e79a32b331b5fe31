#include "render/bench_rendering.h"

#include <tuple>

#include "render/gl_features.h"

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

BenchRendering open_bench_rendering(const RunSpec& spec, const BenchScene& scene, BenchConfig& config,
                                    SettingText* warning) {
  RendererConfig renderer;
  std::tie(renderer.width, renderer.height) = resolution_size(spec.resolution);
  renderer.hide_features = gl_hide_from_environment();
  BenchRendering rendering =
      open_rendering(*parse_backend(spec.backend), scene.characters, config.crowd.copies, renderer, warning);
  config.renderer = rendering.renderer.get();
  return rendering;
}

}  // namespace crowdprof

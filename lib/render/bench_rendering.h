// What a bench needs to draw its frames: a GL context of the chosen backend and
// a crowd renderer, or nothing for --backend none.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "asset/character.h"
#include "frame/bench_setup.h"
#include "frame/run_spec.h"
#include "render/crowd_renderer.h"
#include "render/gl_context.h"

namespace crowdprof {

struct BenchRendering {
  std::unique_ptr<GlContext> context;
  std::unique_ptr<GlCrowdRenderer> renderer;  // null with no backend

  // For the report: "egl", "osmesa" or "none"; the GL_RENDERER and platform.
  std::string backend_name() const;
  std::string renderer_name() const;
};

// Opens `choice` (gl_context.h: auto falls back to none, saying why in
// *warning) and makes a renderer of `config` for `copies` copies. Throws
// GlUnavailable for an explicit backend that fails, UsageError for a
// resolution the GL cannot render, GlError for shaders.
BenchRendering open_rendering(BackendChoice choice, std::span<const Character* const> characters, size_t copies,
                              const RendererConfig& config, SettingText* warning);
BenchRendering open_rendering(BackendChoice choice, const Character& character, size_t copies,
                              const RendererConfig& config, SettingText* warning);

// Opens the spec's backend at its resolution for the config's crowd and points
// config.renderer at its renderer (left null for none). When auto finds no GL,
// `warning` says so and the run goes on without.
BenchRendering open_bench_rendering(const RunSpec& spec, const BenchScene& scene, BenchConfig& config,
                                    SettingText* warning);

}  // namespace crowdprof

// Draws the crowd with GL. The renderer holds what every technique shares (the
// framebuffer, each character's meshes, the GPU timer) and picks, per frame,
// the techniques the copies need from the mode's switches (lib/render/
// techniques/): CPU-skinned copies first, then those the vertex shader skins
// from uniform or buffer palettes, per copy or instanced, then compute and
// baked. The switches are read at every draw: one renderer draws every mode
// of a compare in turn.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "asset/character.h"
#include "frame/frame_renderer.h"
#include "base/modes.h"
#include "render/draw_passes.h"
#include "render/framebuffer.h"
#include "render/gl.h"
#include "render/gl_context.h"
#include "render/gl_features.h"
#include "render/character_meshes.h"
#include "render/gpu_timer.h"
#include "render/techniques/baked.h"
#include "render/techniques/buffer_palette.h"
#include "render/techniques/compute.h"
#include "render/techniques/instanced.h"
#include "render/techniques/software_upload.h"
#include "render/techniques/uniform_palette.h"

namespace crowdprof {

// What no copy covers, linear RGB 0..1 (the PNG holds it unchanged).
inline constexpr float kBackground[3] = {0.09f, 0.10f, 0.12f};

// Empty when skinning `site` can run on a GL with `features`, else the missing
// feature in one phrase ("compute shaders with 3 shader storage buffers (...)").
std::string missing_gl_feature(SkinningSite site, const GlFeatures& features);

struct RendererConfig {
  int width = 1600, height = 900;  // the thesis's window
  // The thesis's cap on the vertex shader's bone array. Tests lower it to make
  // a character fall back to CPU skinning.
  size_t joint_cap = 128;
  // Features to act as if the GL lacked (gl_features.h; CROWDPROF_GL_HIDE).
  std::string hide_features;
};

// The bone limit of the thesis (4.4): half the vertex stage's uniform
// components, in 16-float matrices, at most `cap`. On Mesa and NVIDIA (4,096
// components) that is 128.
size_t gpu_joint_limit(GLint max_vertex_uniform_components, size_t cap);

class GlCrowdRenderer final : public FrameRenderer {
 public:
  // Makes the framebuffer, compiles the shaders and uploads what never
  // changes: each character's index buffer and, for GPU skinning, its rest
  // mesh with its joints and weights. `context` must be current now and at
  // every call, and outlive the renderer, as must the characters (a bench
  // draws with the same list). `copies` sizes the per-frame vertex buffers.
  // Throws UsageError (resolution) or GlError.
  GlCrowdRenderer(GlContext& context, std::span<const Character* const> characters, size_t copies,
                  const RendererConfig& config);
  GlCrowdRenderer(GlContext& context, const Character& character, size_t copies, const RendererConfig& config);
  ~GlCrowdRenderer() override;
  GlCrowdRenderer(const GlCrowdRenderer&) = delete;
  GlCrowdRenderer& operator=(const GlCrowdRenderer&) = delete;

  size_t max_gpu_joints(const ModeSwitches& mode) const override;
  // Throws GlUnavailable naming the feature the mode needs that the GL lacks.
  void require(const ModeSwitches& mode) const override;
  const GlFeatures& features() const { return features_; }
  // Modes compute and baked: builds their programs and buffers, and uploads
  // the baked tables (and, frustum gpu, every copy's box, clock and placement).
  void prepare(const FrameView& view) override;
  uint64_t animation_gpu_bytes() const override { return animation_gpu_bytes_; }
  GpuMemoryRecord gpu_memory() const override;
  // Uploads and draws every copy that view.visible says is on screen.
  // Throws GlError "GL error ... during Rasterizer".
  void draw(const FrameView& view, Counters& counters) override;
  // glFinish. Throws GlError "GL error ... during GPU Latency".
  void finish() override;
  bool gpu_visible_counts(const FrameView& view, std::span<uint64_t> per_group) const override;
  std::string gpu_timing_missing() const override;
  std::string pipeline_statistics_missing() const override;
  size_t take_gpu_times(const FrameView* owner, uint64_t frame, std::span<GpuTime> out, bool wait) override;
  double gpu_timer_resolution_ms() const override { return features_.timer_queries() ? timer_.resolution_ms() : 0; }

  // The last frame drawn, RGBA8, rows top to bottom.
  std::vector<uint8_t> read_pixels() const { return framebuffer_.read_rgba(); }
  int width() const { return framebuffer_.width(); }
  int height() const { return framebuffer_.height(); }
  const GlContext& context() const { return context_; }

 private:
  GlContext& context_;
  Framebuffer framebuffer_;
  GlFeatures features_;
  size_t max_joints_ = 0;  // the uniform array's bone limit
  CharacterMeshes meshes_;
  GpuTimer timer_;                // when features_.timer_queries()
  ShadowMaps shadow_maps_;        // passes > 2: one per cascade, kept for later benches
  std::vector<DrawPass> passes_;  // scratch: this frame's
  void bind_pass(const DrawPass& pass, bool after_prepass);
  // The techniques: made when the GL and the characters allow them
  // (compute and baked when a bench first asks for them).
  std::unique_ptr<SoftwareUpload> software_;
  std::unique_ptr<UniformPalette> uniform_palette_;
  std::unique_ptr<BufferPalette> buffer_palette_;
  std::unique_ptr<Instanced> instanced_;
  std::unique_ptr<ComputeSkinning> compute_;
  std::unique_ptr<BakedSkinning> baked_;
  uint64_t animation_gpu_bytes_ = 0;  // of the last bench prepared
};

}  // namespace crowdprof

#include "render/crowd_renderer.h"

#include <algorithm>
#include <array>

#include "frame/frame_view.h"
#include "render/gl_errors.h"

namespace crowdprof {

namespace {

// Storage buffers compute and baked each bind in one stage (skin.comp: rest,
// bones, skinned; baked.vert: its table, the records arriving as attributes).
constexpr GLint kComputeStorageBlocks = 3, kBakedStorageBlocks = 1;

}  // namespace

std::string missing_gl_feature(SkinningSite site, const GlFeatures& features) {
  if (site == SkinningSite::Compute && features.compute_storage_blocks < kComputeStorageBlocks)
    return "compute shaders with " + std::to_string(kComputeStorageBlocks) +
           " shader storage buffers (GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS is " +
           std::to_string(features.compute_storage_blocks) + ")";
  if (site == SkinningSite::Baked &&
      (features.vertex_storage_blocks < kBakedStorageBlocks || features.max_storage_block_bytes <= 0))
    return "shader storage buffers in the vertex shader (GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS is " +
           std::to_string(features.vertex_storage_blocks) + ")";
  return {};
}

size_t gpu_joint_limit(GLint max_vertex_uniform_components, size_t cap) {
  size_t components = static_cast<size_t>(std::max(max_vertex_uniform_components, 0));
  return std::min(cap, components / 2 / 16);
}

GlCrowdRenderer::GlCrowdRenderer(GlContext& context, const Character& character, size_t copies,
                                 const RendererConfig& config)
    : GlCrowdRenderer(context, std::span<const Character* const>(std::array<const Character*, 1>{&character}), copies,
                      config) {}

GlCrowdRenderer::GlCrowdRenderer(GlContext& context, std::span<const Character* const> characters, size_t copies,
                                 const RendererConfig& config)
    : context_(context),
      framebuffer_(config.width, config.height),
      features_(read_gl_features(config.hide_features)),
      meshes_(characters) {
  GLint uniform_components = 0;
  glGetIntegerv(GL_MAX_VERTEX_UNIFORM_COMPONENTS, &uniform_components);
  max_joints_ = gpu_joint_limit(uniform_components, config.joint_cap);
  software_ = std::make_unique<SoftwareUpload>(meshes_, copies);
  bool any_fits = false;
  for (size_t k = 0; k < meshes_.size(); ++k) any_fits |= meshes_[k].joints <= max_joints_;
  if (any_fits && max_joints_ > 0) uniform_palette_ = std::make_unique<UniformPalette>(meshes_, max_joints_);
  // Buffer palettes know no bone limit: every character gets its rest mesh.
  if (features_.storage_buffers()) {
    buffer_palette_ = std::make_unique<BufferPalette>(meshes_, features_);
    instanced_ = std::make_unique<Instanced>(meshes_, features_);
  }
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
  // glTF's front faces wind counter-clockwise; the backs of a closed mesh are
  // hidden anyway, and culling them halves the rasteriser's work, as in the BGE.
  glEnable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  check_gl("renderer set-up");
}

GlCrowdRenderer::~GlCrowdRenderer() = default;

size_t GlCrowdRenderer::max_gpu_joints(const ModeSwitches& mode) const {
  if (mode.palettes == PaletteStorage::Uniforms) return max_joints_;
  // One copy's palette must fit the storage block; the crowd's is checked when drawn.
  return static_cast<size_t>(std::max<int64_t>(features_.max_storage_block_bytes, 0)) / (3 * sizeof(glm::vec4));
}

void GlCrowdRenderer::require(const ModeSwitches& mode) const {
  if (std::string missing = missing_gl_feature(mode.skinning, features_); !missing.empty())
    throw GlUnavailable("skinning " + std::string(to_string(mode.skinning)) + " needs " + missing + ", which " +
                        context_.renderer() + " lacks");
  if (mode.frustum == FrustumTest::Gpu) {
    if (std::string missing = missing_gl_feature(SkinningSite::Compute, features_); !missing.empty())
      throw GlUnavailable("frustum gpu needs " + missing + ", which " + context_.renderer() + " lacks");
  }
  if (mode.skinning != SkinningSite::Gpu || mode.palettes != PaletteStorage::Buffer) return;
  if (!features_.storage_buffers())
    throw GlUnavailable(context_.renderer() +
                            " offers no shader storage buffers in the vertex stage "
                            "(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS is 0), ",
                        "which {palettes} buffer needs: use {palettes} uniforms (mode hwskin)");
}

void GlCrowdRenderer::prepare(const FrameView& view) {
  bool any_compute = false, any_baked = false;
  for (size_t k = 0; k < meshes_.size(); ++k) {
    any_compute |= view.characters[k].site == SkinningSite::Compute;
    any_baked |= view.characters[k].site == SkinningSite::Baked;
  }
  require(view.mode);
  for (size_t k = 0; k < meshes_.size(); ++k) meshes_.upload_levels(k, view.characters[k].mesh_lods);
  uint64_t bytes = 0;
  if (any_compute) {
    if (!compute_) compute_ = std::make_unique<ComputeSkinning>();
    compute_->prepare(view, meshes_);
    bytes += compute_->gpu_bytes();
  }
  if (any_baked) {
    if (!baked_) baked_ = std::make_unique<BakedSkinning>(features_);
    baked_->prepare(view, meshes_);
    bytes += baked_->gpu_bytes();
  }
  shadow_maps_.reserve(view.shadow_view_projections.size());
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  glBindVertexArray(0);
  framebuffer_.bind();
  animation_gpu_bytes_ = bytes;
  check_gl("renderer set-up for skinning " + std::string(to_string(view.mode.skinning)));
}

void GlCrowdRenderer::bind_pass(const DrawPass& pass, bool after_prepass) {
  if (pass.kind == GpuPass::Shadows)
    shadow_maps_.bind_and_clear(pass.cascade);
  else
    framebuffer_.bind();
  GLboolean colour = pass.colour() ? GL_TRUE : GL_FALSE;
  glColorMask(colour, colour, colour, colour);
  // After a prepass the colour pass meets the depth it wrote: equal passes.
  glDepthFunc(pass.colour() && after_prepass ? GL_LEQUAL : GL_LESS);
}

void GlCrowdRenderer::draw(const FrameView& view, Counters& counters) {
  // The GPU's time for everything the frame asks of it, clear to last draw,
  // and each pass's share of it.
  const bool timed = features_.timer_queries();
  if (timed) timer_.begin(&view, view.frame, features_.pipeline_statistics);
  framebuffer_.bind();
  glClearColor(kBackground[0], kBackground[1], kBackground[2], 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  // Copies skinned on the CPU first, then those the vertex shader skins, then
  // the compute and baked passes: one program switch a frame (per technique
  // and pass), whatever the mix.
  bool any_cpu = false, any_gpu = false, any_compute = false, any_baked = false;
  for (size_t k = 0; k < meshes_.size(); ++k) {
    SkinningSite site = view.characters[k].site;
    any_cpu |= !skins_on_gpu(view.characters[k].site);
    any_gpu |= site == SkinningSite::Gpu;
    any_compute |= site == SkinningSite::Compute;
    any_baked |= site == SkinningSite::Baked;
  }
  const ModeSwitches& mode = view.mode;
  std::array<Technique*, 3> techniques{};
  size_t count = 0;
  if (any_cpu) techniques[count++] = software_.get();
  if (any_gpu && mode.palettes == PaletteStorage::Uniforms) {
    if (!uniform_palette_) throw GlError("GPU skinning asked of a renderer whose character is over its bone limit");
    techniques[count++] = uniform_palette_.get();
  }
  if (any_gpu && mode.palettes == PaletteStorage::Buffer) {
    require(mode);
    techniques[count++] = mode.draw == DrawMethod::Instanced ? static_cast<Technique*>(instanced_.get())
                                                             : static_cast<Technique*>(buffer_palette_.get());
  }
  passes_ = draw_passes(view);
  if (view.shadow_view_projections.size() > shadow_maps_.count())
    throw GlError("shadow cascades asked of a renderer not prepared for them");
  const bool prepass = mode.passes >= 2;
  auto begin_pass = [&](const DrawPass* pass) {
    if (pass) bind_pass(*pass, prepass);
    if (timed) timer_.mark(pass ? pass->kind : GpuPass::Skinning);
  };
  auto run = [&](std::span<Technique* const> list) {
    begin_pass(nullptr);
    for (Technique* t : list) t->upload(view, meshes_, counters);
    for (const DrawPass& pass : passes_) {
      begin_pass(&pass);
      for (Technique* t : list) t->draw(view, meshes_, pass, counters);
    }
  };
  if (count > 0) run(std::span<Technique* const>(techniques.data(), count));
  if (any_compute) {
    if (!compute_) throw GlError("compute skinning asked of a renderer not prepared for it");
    compute_->draw(view, meshes_, passes_, begin_pass, counters);
  }
  if (any_baked) {
    if (!baked_) throw GlError("baked skinning asked of a renderer not prepared for it");
    Technique* baked = baked_.get();
    run(std::span<Technique* const>(&baked, 1));
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_LESS);
  framebuffer_.bind();
  glBindVertexArray(0);
  if (timed) timer_.end();
  check_gl("Rasterizer");
}

void GlCrowdRenderer::finish() {
  glFinish();
  check_gl("GPU Latency");
}

bool GlCrowdRenderer::gpu_visible_counts(const FrameView& view, std::span<uint64_t> per_group) const {
  if (!baked_ || !baked_->visible_counts(view, per_group)) return false;
  check_gl("Overhead (reading the cull pass's counts)");
  return true;
}

std::string GlCrowdRenderer::gpu_timing_missing() const {
  if (features_.timer_queries()) return {};
  return context_.renderer() + " has no GL_TIME_ELAPSED timer (0 counter bits)";
}

GpuMemoryRecord GlCrowdRenderer::gpu_memory() const {
  GpuMemoryRecord m;
  m.source = features_.memory_source;
  if (features_.memory_total_kib >= 0) m.total_bytes = static_cast<uint64_t>(features_.memory_total_kib) * 1024;
  if (features_.memory_free_kib >= 0) m.free_bytes = static_cast<uint64_t>(features_.memory_free_kib) * 1024;
  m.max_storage_block_bytes = static_cast<uint64_t>(std::max<int64_t>(features_.max_storage_block_bytes, 0));
  return m;
}

std::string GlCrowdRenderer::pipeline_statistics_missing() const {
  if (!features_.timer_queries()) return gpu_timing_missing();
  if (features_.pipeline_statistics) return {};
  return context_.renderer() + " lacks ARB_pipeline_statistics_query";
}

size_t GlCrowdRenderer::take_gpu_times(const FrameView* owner, uint64_t frame, std::span<GpuTime> out, bool wait) {
  if (!features_.timer_queries()) return 0;
  size_t taken = timer_.take(owner, frame, out, wait);
  check_gl("Overhead (reading GPU timer queries)");
  return taken;
}

}  // namespace crowdprof

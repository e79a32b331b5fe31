// Draws the crowd with GL, one draw per copy on screen (the BGE drew each mesh
// on its own too). Copies skinned on the CPU have their vertices uploaded every
// frame; with skinning on the GPU (thesis 4.4) the rest mesh is uploaded once
// and each frame sends only the skinning matrices, as a uniform array, or
// (--palettes buffer) every copy's palette in one shader storage buffer, drawn
// per copy or (--draw instanced) with one instanced draw per character kind.
// The mode's switches are read at every draw: one renderer draws every mode of
// a compare in turn.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "asset/character.h"
#include "frame/frame_renderer.h"
#include "frame/modes.h"
#include "render/framebuffer.h"
#include "render/gl.h"
#include "render/gl_context.h"
#include "render/gl_features.h"
#include "render/gl_program.h"
#include "render/gpu_frame_buffers.h"
#include "render/gpu_timer.h"

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
  // the baked tables and every copy's placement.
  void prepare(const CrowdBench& bench) override;
  uint64_t animation_gpu_bytes() const override { return animation_gpu_bytes_; }
  // Uploads and draws every copy that bench.visible() says is on screen.
  // Throws GlError "GL error ... during Rasterizer".
  void draw(const CrowdBench& bench, Counters& counters) override;
  // glFinish. Throws GlError "GL error ... during GPU Latency".
  void finish() override;
  std::string gpu_timing_missing() const override;
  size_t take_gpu_times(const CrowdBench& owner, uint64_t frame, std::span<GpuTime> out, bool wait) override;
  double gpu_timer_resolution_ms() const override { return features_.timer_queries() ? timer_.resolution_ms() : 0; }

  // The last frame drawn, RGBA8, rows top to bottom.
  std::vector<uint8_t> read_pixels() const { return framebuffer_.read_rgba(); }
  int width() const { return framebuffer_.width(); }
  int height() const { return framebuffer_.height(); }
  const GlContext& context() const { return context_; }

  // Bytes one copy of character `kind` costs to send each frame: its skinned
  // positions and normals, or its skinning matrices (3 rows of 4 floats
  // each); plus its world matrix.
  uint64_t vertex_bytes_per_copy(size_t kind = 0) const;
  uint64_t bone_bytes_per_copy(size_t kind = 0) const;
  // Instanced drawing: the palette and the instance record.
  uint64_t instance_bytes_per_copy(size_t kind = 0) const;

 private:
  void draw_copy_cpu_skinned(const CrowdBench& bench, size_t copy, size_t drawn, Counters& counters);
  void draw_copy_gpu_skinned(const CrowdBench& bench, size_t copy, Counters& counters);
  // --vertex-format packed: the same stream buffers, read as 16-bit position
  // codes and 10:10:10:2 normals by a program that decodes them.
  void draw_copy_packed(const CrowdBench& bench, size_t copy, size_t drawn, Counters& counters);
  // The GPU-skinned copies with their palettes in frame_buffers_: per copy or instanced.
  void draw_buffer_palettes(const CrowdBench& bench, bool instanced, Counters& counters);
  void set_frame_uniforms(const GlProgram& program, const CrowdBench& bench) const;
  void draw_compute_skinned(const CrowdBench& bench, size_t kind, Counters& counters);
  void draw_baked(const CrowdBench& bench, Counters& counters);

  // What one character's copies are drawn with.
  struct Kind {
    size_t vertices = 0, joints = 0;
    GLsizei index_count = 0;
    GLuint indices = 0;
    // GPU skinning: the rest mesh, uploaded once (when the character fits).
    GLuint gpu_vao = 0, rest_buffers[4] = {0, 0, 0, 0};
    GLuint rest_storage = 0;  // compute: the rest mesh as a storage buffer, 64 bytes a vertex
    GLuint baked_table = 0;   // baked: every sample's 3x4 rows, 48 bytes a joint
    uint64_t baked_bytes = 0;
    GLuint instanced_vao = 0;  // the same, and each instance's record (--draw instanced)
  };

  // The rest mesh, joints and weights of a GPU-skinned character, uploaded once.
  void make_rest_mesh(Kind& kind, const SkinnedMesh& mesh);

  GlContext& context_;
  Framebuffer framebuffer_;
  size_t max_joints_ = 0;
  std::vector<Kind> kinds_;  // per character
  GlFeatures features_;
  GlProgram cpu_program_, gpu_program_;
  GLint cpu_model_ = -1, cpu_colour_ = -1, gpu_model_ = -1, gpu_colour_ = -1, gpu_bones_ = -1;
  // --palettes buffer: per copy and instanced (when the GL has vertex SSBOs).
  GlProgram buffer_program_, instanced_program_;
  GLint buffer_model_ = -1, buffer_colour_ = -1, buffer_base_ = -1;
  GpuFrameBuffers frame_buffers_;
  GpuTimer timer_;  // when features_.timer_queries()
  std::vector<uint32_t> kind_counts_;  // scratch: GPU-skinned copies on screen per kind
  // CPU-skinned copies: a buffer per drawn copy (positions, then normals),
  // orphaned and refilled every frame. With more copies on screen than
  // buffers, buffers serve several copies.
  GLuint cpu_vao_ = 0;
  GlProgram packed_program_;
  GLint packed_model_ = -1, packed_colour_ = -1, packed_min_ = -1, packed_extent_ = -1;
  GLuint packed_vao_ = 0;
  std::vector<GLuint> stream_;
  // With animation sharing, the storage (bench.storage_of) whose mesh the last
  // CPU-skinned draw uploaded, and the buffer holding it: copies in the same
  // state after it draw that buffer with their own transform, uploading nothing.
  size_t shown_storage_ = SIZE_MAX;
  GLuint shown_buffer_ = 0;
  std::vector<glm::vec4> bone_rows_;  // scratch: one copy's 3 x joints rows

  uint64_t animation_gpu_bytes_ = 0;  // of the last bench prepared
  uint64_t compute_gpu_bytes_ = 0, baked_gpu_bytes_ = 0;  // what each of those modes holds
  // compute: a batch of copies' palettes in, their skinned vertices out.
  GlProgram compute_program_;
  GLint compute_vertex_count_ = -1, compute_joint_count_ = -1;
  GLuint compute_vao_ = 0, compute_bones_ = 0, compute_skinned_ = 0;
  size_t compute_batch_ = 0, compute_vertices_ = 0, compute_joints_ = 0;  // sizes the buffers hold
  std::vector<glm::vec4> compute_rows_;  // scratch: a batch's palettes
  std::vector<size_t> batch_copies_;     // scratch: a kind's visible copies
  // baked: placements (model, colour) of every copy, uploaded at prepare, and
  // this frame's instances (copy, first sample, intervals, position).
  GlProgram baked_program_;
  GLint baked_joint_count_ = -1, baked_first_instance_ = -1;
  GLuint placements_ = 0, instances_ = 0;
  size_t instance_capacity_ = 0;
  struct InstanceRecord {
    uint32_t copy, first_sample, intervals;
    float position;
  };
  static_assert(sizeof(InstanceRecord) == 16);
  std::vector<InstanceRecord> instance_records_;  // scratch: this frame's, grouped by character
};

}  // namespace crowdprof

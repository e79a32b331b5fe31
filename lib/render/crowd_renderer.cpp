#include "render/crowd_renderer.h"

#include <algorithm>
#include <array>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "frame/crowd_bench.h"
#include "render/gl_errors.h"
#include "render/shader_sources.h"

namespace crowdprof {

namespace {

// The per-frame vertex buffers hold at most this much: enough for every copy of
// the thesis scene (160 x 119 KB), bounded for crowds of thousands.
constexpr size_t kStreamBudgetBytes = size_t{64} << 20;

// A few colours so that neighbours in the crowd can be told apart.
constexpr std::array<glm::vec3, 6> kPalette = {{{0.80f, 0.45f, 0.30f},
                                                {0.35f, 0.55f, 0.80f},
                                                {0.55f, 0.75f, 0.40f},
                                                {0.85f, 0.75f, 0.35f},
                                                {0.65f, 0.45f, 0.75f},
                                                {0.75f, 0.75f, 0.75f}}};

GLuint make_buffer(GLenum target, size_t bytes, const void* data, GLenum usage) {
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(target, buffer);
  glBufferData(target, static_cast<GLsizeiptr>(bytes), data, usage);
  return buffer;
}

void float_attribute(GLuint index, GLuint buffer, GLint components) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glEnableVertexAttribArray(index);
  glVertexAttribPointer(index, components, GL_FLOAT, GL_FALSE, 0, nullptr);
}

std::vector<ShaderStage> stages(const char* vertex, const std::string& defines,
                                const std::string& fragment_defines = {}) {
  return {{GL_VERTEX_SHADER, vertex, with_defines(embedded_shader(vertex), defines)},
          {GL_FRAGMENT_SHADER, "shaders/lit.frag", with_defines(embedded_shader("shaders/lit.frag"), fragment_defines)}};
}

// The buffer-palette programs: shaders/instances.glsl ahead of buffer_skin.vert.
std::vector<ShaderStage> buffer_stages(bool instanced) {
  std::string defines = instanced ? "#define INSTANCED\n#define COLOURS " + std::to_string(kPalette.size()) + "\n" : "";
  defines += std::string(embedded_shader("shaders/instances.glsl"));
  return stages("shaders/buffer_skin.vert", defines, instanced ? "#define INSTANCED\n" : "");
}

// The 3x4 upper part of a column-major matrix, as rows (the fourth row of an
// affine matrix is always 0 0 0 1).
void put_rows(const SkinMatrix& m, glm::vec4* rows) {
  for (int r = 0; r < 3; ++r) rows[r] = glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
}

// The compute pass's vertex buffer holds at most this much (a batch of copies).
constexpr size_t kComputeBudgetBytes = size_t{64} << 20;
constexpr GLuint kComputeGroup = 64;  // skin.comp's local_size_x
// Storage buffers each mode binds in one stage (skin.comp: rest, bones,
// skinned; baked.vert: table, placements, instances).
constexpr GLint kStorageBlocksNeeded = 3;

}  // namespace

std::string missing_gl_feature(SkinningSite site, const GlFeatures& features) {
  if (site == SkinningSite::Compute && features.compute_storage_blocks < kStorageBlocksNeeded)
    return "compute shaders with " + std::to_string(kStorageBlocksNeeded) +
           " shader storage buffers (GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS is " +
           std::to_string(features.compute_storage_blocks) + ")";
  if (site == SkinningSite::Baked &&
      (features.vertex_storage_blocks < kStorageBlocksNeeded || features.max_storage_block_bytes <= 0))
    return "shader storage buffers in the vertex shader, " + std::to_string(kStorageBlocksNeeded) +
           " of them (GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS is " + std::to_string(features.vertex_storage_blocks) + ")";
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
    : context_(context), framebuffer_(config.width, config.height) {
  features_ = read_gl_features(config.hide_features);
  GLint uniform_components = 0;
  glGetIntegerv(GL_MAX_VERTEX_UNIFORM_COMPONENTS, &uniform_components);
  max_joints_ = gpu_joint_limit(uniform_components, config.joint_cap);

  cpu_program_ = GlProgram(stages("shaders/crowd.vert", ""));
  cpu_model_ = cpu_program_.uniform("model");
  cpu_colour_ = cpu_program_.uniform("base_colour");
  size_t max_vertices = 0, max_fitting_joints = 0;
  for (const Character* character : characters) {
    const SkinnedMesh& mesh = character->mesh;
    Kind kind;
    kind.vertices = mesh.vertex_count();
    kind.joints = character->skeleton.joint_count();
    kind.index_count = static_cast<GLsizei>(mesh.indices.size());
    kind.indices = make_buffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices.size() * sizeof(uint32_t), mesh.indices.data(),
                               GL_STATIC_DRAW);
    max_vertices = std::max(max_vertices, kind.vertices);
    kinds_.push_back(kind);
  }

  // CPU-skinned copies: one buffer per copy drawn, as the BGE gave each mesh
  // its own, so that a copy's upload never waits on another copy's draw.
  size_t copy_bytes = std::max<size_t>(2 * max_vertices * sizeof(glm::vec3), 1);
  stream_.resize(std::clamp<size_t>(kStreamBudgetBytes / copy_bytes, 1, std::max<size_t>(copies, 1)));
  for (GLuint& buffer : stream_) buffer = make_buffer(GL_ARRAY_BUFFER, copy_bytes, nullptr, GL_STREAM_DRAW);
  // Attributes 0 and 1 read bindings 0 and 1, which each draw points at its buffer.
  glGenVertexArrays(1, &cpu_vao_);
  glBindVertexArray(cpu_vao_);
  for (GLuint attribute : {0u, 1u}) {
    glEnableVertexAttribArray(attribute);
    glVertexAttribFormat(attribute, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexAttribBinding(attribute, attribute);
  }

  // Packed vertices: positions as 3 normalised 16-bit codes, normals as one
  // signed normalised 10:10:10:2 word (its 2-bit w unused by the shader).
  packed_program_ = GlProgram(stages("shaders/crowd.vert", "#define PACKED_POSITIONS 1\n"));
  packed_model_ = packed_program_.uniform("model");
  packed_colour_ = packed_program_.uniform("base_colour");
  packed_min_ = packed_program_.uniform("position_min");
  packed_extent_ = packed_program_.uniform("position_extent");
  glGenVertexArrays(1, &packed_vao_);
  glBindVertexArray(packed_vao_);
  glEnableVertexAttribArray(0);
  glVertexAttribFormat(0, 3, GL_UNSIGNED_SHORT, GL_TRUE, 0);
  glVertexAttribBinding(0, 0);
  glEnableVertexAttribArray(1);
  glVertexAttribFormat(1, 4, GL_INT_2_10_10_10_REV, GL_TRUE, 0);
  glVertexAttribBinding(1, 1);

  for (size_t k = 0; k < kinds_.size(); ++k) {
    Kind& kind = kinds_[k];
    if (kind.joints > max_joints_ || max_joints_ == 0) continue;
    if (!gpu_program_.id()) {
      gpu_program_ = GlProgram(stages("shaders/hwskin.vert", "#define MAX_BONES " + std::to_string(max_joints_) + "\n"));
      gpu_model_ = gpu_program_.uniform("model");
      gpu_colour_ = gpu_program_.uniform("base_colour");
      gpu_bones_ = gpu_program_.uniform("bones");
    }
    make_rest_mesh(kind, characters[k]->mesh);
    max_fitting_joints = std::max(max_fitting_joints, kind.joints);
  }
  bone_rows_.resize(3 * max_fitting_joints);
  // Buffer palettes know no bone limit: every character gets its rest mesh.
  if (features_.storage_buffers()) {
    buffer_program_ = GlProgram(buffer_stages(false));
    buffer_model_ = buffer_program_.uniform("model");
    buffer_colour_ = buffer_program_.uniform("base_colour");
    buffer_base_ = buffer_program_.uniform("palette_base");
    instanced_program_ = GlProgram(buffer_stages(true));

    for (size_t k = 0; k < kinds_.size(); ++k)
      if (!kinds_[k].gpu_vao) make_rest_mesh(kinds_[k], characters[k]->mesh);
  }
  kind_counts_.resize(kinds_.size());
  glBindVertexArray(0);

  glEnable(GL_DEPTH_TEST);
  // glTF's front faces wind counter-clockwise; the backs of a closed mesh are
  // hidden anyway, and culling them halves the rasteriser's work, as in the BGE.
  glEnable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  check_gl("renderer set-up");
}

void GlCrowdRenderer::make_rest_mesh(Kind& kind, const SkinnedMesh& mesh) {
  size_t vertices = kind.vertices;
  kind.rest_buffers[0] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec3), mesh.positions.data(), GL_STATIC_DRAW);
  kind.rest_buffers[1] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec3), mesh.normals.data(), GL_STATIC_DRAW);
  kind.rest_buffers[2] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::u16vec4), mesh.joints.data(), GL_STATIC_DRAW);
  kind.rest_buffers[3] = make_buffer(GL_ARRAY_BUFFER, vertices * sizeof(glm::vec4), mesh.weights.data(), GL_STATIC_DRAW);
  // Two VAOs on the same buffers: one per copy, and one for instanced draws
  // that also reads each instance's record.
  for (GLuint* vao : {&kind.gpu_vao, &kind.instanced_vao}) {
    glGenVertexArrays(1, vao);
    glBindVertexArray(*vao);
    float_attribute(0, kind.rest_buffers[0], 3);
    float_attribute(1, kind.rest_buffers[1], 3);
    glBindBuffer(GL_ARRAY_BUFFER, kind.rest_buffers[2]);
    glEnableVertexAttribArray(2);
    glVertexAttribIPointer(2, 4, GL_UNSIGNED_SHORT, 0, nullptr);
    float_attribute(3, kind.rest_buffers[3], 4);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, kind.indices);
  }
  // The records of shaders/instances.glsl as per-instance attributes 4-8 (the
  // model's columns, then palette offset, colour and the source words): llvmpipe
  // fetches them once per instance, where reading them from the storage buffer
  // costs a gather per vertex (1.2x the CPU time, docs/rendering.md).
  for (GLuint column = 0; column < 4; ++column) {
    glEnableVertexAttribArray(4 + column);
    glVertexAttribFormat(4 + column, 4, GL_FLOAT, GL_FALSE, column * static_cast<GLuint>(sizeof(glm::vec4)));
    glVertexAttribBinding(4 + column, kInstanceStream);
  }
  glEnableVertexAttribArray(8);
  glVertexAttribIFormat(8, 4, GL_UNSIGNED_INT, static_cast<GLuint>(sizeof(glm::mat4)));
  glVertexAttribBinding(8, kInstanceStream);
  glVertexBindingDivisor(kInstanceStream, 1);
}

size_t GlCrowdRenderer::max_gpu_joints(const ModeSwitches& mode) const {
  if (mode.palettes == PaletteStorage::Uniforms) return max_joints_;
  // One copy's palette must fit the storage block; the crowd's is checked when drawn.
  return static_cast<size_t>(std::max<int64_t>(features_.max_storage_block_bytes, 0)) / (3 * sizeof(glm::vec4));
}

void GlCrowdRenderer::require(const ModeSwitches& mode) const {
  if (std::string missing = missing_gl_feature(mode.skinning, features_); !missing.empty())
    throw GlUnavailable("skinning " + std::string(to_string(mode.skinning)) + " needs " + missing + ", which " +
                        context_.renderer() + " lacks");
  if (mode.skinning != SkinningSite::Gpu || mode.palettes != PaletteStorage::Buffer) return;
  if (!features_.storage_buffers())
    throw GlUnavailable(context_.renderer() + " offers no shader storage buffers in the vertex stage "
                        "(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS is 0), which --palettes buffer needs: use --palettes "
                        "uniforms (mode hwskin)");
}

GlCrowdRenderer::~GlCrowdRenderer() {
  glDeleteVertexArrays(1, &cpu_vao_);
  glDeleteVertexArrays(1, &compute_vao_);
  glDeleteVertexArrays(1, &packed_vao_);
  glDeleteBuffers(static_cast<GLsizei>(stream_.size()), stream_.data());
  GLuint shared[] = {compute_bones_, compute_skinned_, placements_, instances_};
  glDeleteBuffers(4, shared);
  for (Kind& kind : kinds_) {
    glDeleteVertexArrays(1, &kind.gpu_vao);
    glDeleteVertexArrays(1, &kind.instanced_vao);
    glDeleteBuffers(1, &kind.indices);
    glDeleteBuffers(4, kind.rest_buffers);
    glDeleteBuffers(1, &kind.rest_storage);
    glDeleteBuffers(1, &kind.baked_table);
  }
}

void GlCrowdRenderer::prepare(const CrowdBench& bench) {
  bool any_compute = false, any_baked = false;
  for (size_t k = 0; k < kinds_.size(); ++k) {
    any_compute |= bench.site_of_kind(k) == SkinningSite::Compute;
    any_baked |= bench.site_of_kind(k) == SkinningSite::Baked;
  }
  require(bench.config().mode);
  uint64_t bytes = 0;
  size_t copies = bench.crowd().size();
  if (any_compute) {
    if (!compute_program_.id()) {
      std::string source(embedded_shader("shaders/skin.comp"));
      ShaderStage stage{GL_COMPUTE_SHADER, "shaders/skin.comp", source};
      compute_program_ = GlProgram(std::span(&stage, 1));
      compute_vertex_count_ = compute_program_.uniform("vertex_count");
      compute_joint_count_ = compute_program_.uniform("joint_count");
      // Positions and normals interleaved, 32 bytes a vertex: attribute 1 is 16 bytes in.
      glGenVertexArrays(1, &compute_vao_);
      glBindVertexArray(compute_vao_);
      for (GLuint attribute : {0u, 1u}) {
        glEnableVertexAttribArray(attribute);
        glVertexAttribFormat(attribute, 3, GL_FLOAT, GL_FALSE, attribute * 16);
        glVertexAttribBinding(attribute, 0);
      }
      glBindVertexArray(0);
    }
    size_t vertices = 1, joints = 1;
    for (size_t k = 0; k < kinds_.size(); ++k) {
      if (bench.site_of_kind(k) != SkinningSite::Compute) continue;
      Kind& kind = kinds_[k];
      vertices = std::max(vertices, kind.vertices);
      joints = std::max(joints, kind.joints);
      if (!kind.rest_storage) {
        const SkinnedMesh& mesh = bench.characters()[k]->mesh;
        std::vector<glm::vec4> rest(4 * kind.vertices);
        for (size_t v = 0; v < kind.vertices; ++v) {
          rest[4 * v] = glm::vec4(mesh.positions[v], 1.0f);
          rest[4 * v + 1] = glm::vec4(mesh.normals[v], 0.0f);
          glm::uvec4 j(mesh.joints[v]);
          std::memcpy(&rest[4 * v + 2], &j, sizeof j);  // uvec4 in the shader: the bits, not the values
          rest[4 * v + 3] = mesh.weights[v];
        }
        kind.rest_storage = make_buffer(GL_SHADER_STORAGE_BUFFER, rest.size() * sizeof(glm::vec4), rest.data(), GL_STATIC_DRAW);
      }
      bytes += kind.vertices * 4 * sizeof(glm::vec4);
    }
    size_t batch = std::clamp<size_t>(kComputeBudgetBytes / (vertices * 2 * sizeof(glm::vec4)), 1, std::max<size_t>(copies, 1));
    batch = std::min<size_t>(batch, 65535);  // the least GL_MAX_COMPUTE_WORK_GROUP_COUNT[1] GL promises
    if (batch != compute_batch_ || vertices != compute_vertices_ || joints != compute_joints_) {
      glDeleteBuffers(1, &compute_bones_);
      glDeleteBuffers(1, &compute_skinned_);
      compute_bones_ = make_buffer(GL_SHADER_STORAGE_BUFFER, batch * joints * 3 * sizeof(glm::vec4), nullptr, GL_STREAM_DRAW);
      compute_skinned_ = make_buffer(GL_SHADER_STORAGE_BUFFER, batch * vertices * 2 * sizeof(glm::vec4), nullptr, GL_STREAM_COPY);
      compute_batch_ = batch;
      compute_vertices_ = vertices;
      compute_joints_ = joints;
      compute_rows_.assign(batch * joints * 3, glm::vec4(0));
    }
    batch_copies_.reserve(copies);
    bytes += compute_batch_ * (compute_joints_ * 3 + compute_vertices_ * 2) * sizeof(glm::vec4);
    compute_gpu_bytes_ = bytes;
  }
  if (any_baked) {
    if (!baked_program_.id()) {
      baked_program_ = GlProgram(stages("shaders/baked.vert", "", "#define INSTANCED\n"));
      baked_joint_count_ = baked_program_.uniform("joint_count");
      baked_first_instance_ = baked_program_.uniform("first_instance");
    }
    for (size_t k = 0; k < kinds_.size(); ++k) {
      const BakedCharacter* baked = bench.site_of_kind(k) == SkinningSite::Baked ? bench.baked(k) : nullptr;
      if (!baked) continue;
      Kind& kind = kinds_[k];
      if (!kind.gpu_vao) make_rest_mesh(kind, bench.characters()[k]->mesh);
      std::vector<glm::vec4> rows(3 * baked->matrices.size());
      for (size_t m = 0; m < baked->matrices.size(); ++m) put_rows(baked->matrices[m], &rows[3 * m]);
      glDeleteBuffers(1, &kind.baked_table);
      kind.baked_bytes = rows.size() * sizeof(glm::vec4);
      kind.baked_table = make_buffer(GL_SHADER_STORAGE_BUFFER, kind.baked_bytes, rows.data(), GL_STATIC_DRAW);
      bytes += kind.baked_bytes;
    }
    // Copies stand still: their placements go up once.
    std::vector<glm::vec4> placements(5 * std::max<size_t>(copies, 1), glm::vec4(0));
    for (size_t i = 0; i < copies; ++i) {
      const glm::mat4& world = bench.crowd().world[i];
      for (int c = 0; c < 4; ++c) placements[5 * i + static_cast<size_t>(c)] = world[c];
      placements[5 * i + 4] = glm::vec4(kPalette[i % kPalette.size()], 1.0f);
    }
    glDeleteBuffers(1, &placements_);
    placements_ = make_buffer(GL_SHADER_STORAGE_BUFFER, placements.size() * sizeof(glm::vec4), placements.data(), GL_STATIC_DRAW);
    if (instance_capacity_ < std::max<size_t>(copies, 1)) {
      instance_capacity_ = std::max<size_t>(copies, 1);
      glDeleteBuffers(1, &instances_);
      instances_ = make_buffer(GL_SHADER_STORAGE_BUFFER, instance_capacity_ * sizeof(InstanceRecord), nullptr, GL_STREAM_DRAW);
    }
    instance_records_.reserve(copies);
    bytes += placements.size() * sizeof(glm::vec4) + instance_capacity_ * sizeof(InstanceRecord);
    baked_gpu_bytes_ = bytes - (any_compute ? compute_gpu_bytes_ : 0);
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  animation_gpu_bytes_ = bytes;
  check_gl("renderer set-up for skinning " + std::string(to_string(bench.config().mode.skinning)));
}

uint64_t GlCrowdRenderer::vertex_bytes_per_copy(size_t kind) const {
  return kinds_[kind].vertices * 2 * sizeof(glm::vec3) + sizeof(glm::mat4);
}
uint64_t GlCrowdRenderer::bone_bytes_per_copy(size_t kind) const {
  return kinds_[kind].joints * 3 * sizeof(glm::vec4) + sizeof(glm::mat4);
}
uint64_t GlCrowdRenderer::instance_bytes_per_copy(size_t kind) const {
  return kinds_[kind].joints * 3 * sizeof(glm::vec4) + sizeof(GpuInstance);
}

void GlCrowdRenderer::set_frame_uniforms(const GlProgram& program, const CrowdBench& bench) const {
  glm::mat4 view_projection = bench.camera().view_projection();
  glUniformMatrix4fv(program.uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(view_projection));
  glm::vec3 light = glm::normalize(glm::vec3(0.4f, 0.8f, 0.6f));  // above, in front, to the right
  glUniform3fv(program.uniform("light_direction"), 1, glm::value_ptr(light));
}

void GlCrowdRenderer::draw(const CrowdBench& bench, Counters& counters) {
  // The GPU's time for everything the frame asks of it, clear to last draw.
  if (features_.timer_queries()) timer_.begin(&bench, bench.frames_run());
  framebuffer_.bind();
  glClearColor(kBackground[0], kBackground[1], kBackground[2], 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const Crowd& crowd = bench.crowd();
  // Copies skinned on the CPU first, then those the vertex shader skins, then
  // the compute and baked passes: one program switch a frame (per pass), whatever the mix.
  bool any_cpu = false, any_gpu = false, any_baked = false;
  for (size_t k = 0; k < kinds_.size(); ++k) {
    SkinningSite site = bench.site_of_kind(k);
    any_cpu |= !bench.gpu_skinned_kind(k);
    any_gpu |= site == SkinningSite::Gpu;
    any_baked |= site == SkinningSite::Baked;
  }
  if (any_cpu) {
    const bool packed = bench.packed_vertices();
    const GlProgram& program = packed ? packed_program_ : cpu_program_;
    glUseProgram(program.id());
    set_frame_uniforms(program, bench);
    glBindVertexArray(packed ? packed_vao_ : cpu_vao_);
    size_t drawn = 0;
    shown_storage_ = SIZE_MAX;
    for (size_t i = 0; i < crowd.size(); ++i) {
      if (!bench.visible(i) || bench.gpu_skinned_copy(i)) continue;
      if (packed)
        draw_copy_packed(bench, i, drawn++, counters);
      else
        draw_copy_cpu_skinned(bench, i, drawn++, counters);
    }
  }
  const ModeSwitches& mode = bench.config().mode;
  if (any_gpu && mode.palettes == PaletteStorage::Uniforms) {
    glUseProgram(gpu_program_.id());
    set_frame_uniforms(gpu_program_, bench);
    for (size_t i = 0; i < crowd.size(); ++i)
      if (bench.visible(i) && bench.site_of_kind(crowd.kind[i]) == SkinningSite::Gpu)
        draw_copy_gpu_skinned(bench, i, counters);
    counters.gpu_palette_bytes = 3 * sizeof(glm::vec4) * max_joints_;  // the uniform array
  }
  if (any_gpu && mode.palettes == PaletteStorage::Buffer)
    draw_buffer_palettes(bench, mode.draw == DrawMethod::Instanced, counters);
  for (size_t k = 0; k < kinds_.size(); ++k)
    if (bench.site_of_kind(k) == SkinningSite::Compute) {
      draw_compute_skinned(bench, k, counters);
      counters.gpu_palette_bytes = compute_gpu_bytes_;
    }
  if (any_baked) {
    draw_baked(bench, counters);
    counters.gpu_palette_bytes = baked_gpu_bytes_;
  }
  glBindVertexArray(0);
  if (features_.timer_queries()) timer_.end();
  check_gl("Rasterizer");
}

void GlCrowdRenderer::draw_copy_cpu_skinned(const CrowdBench& bench, size_t i, size_t drawn, Counters& counters) {
  size_t k = bench.crowd().kind[i];
  const Kind& kind = kinds_[k];
  auto half = static_cast<GLsizeiptr>(kind.vertices * sizeof(glm::vec3));
  // Animation sharing: a copy in the state the last draw uploaded draws that
  // mesh again with its own transform (the thesis scene: one upload a frame).
  bool same_mesh = bench.config().mode.share_poses && bench.storage_of(i) == shown_storage_;
  GLuint buffer = same_mesh ? shown_buffer_ : stream_[drawn % stream_.size()];
  if (!same_mesh) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    // Fresh storage (orphaning) before writing: writing into storage that a
    // draw may still read makes the driver wait for it. llvmpipe waits even
    // for the last frame's finished draws: 2.5x the Rasterizer time without.
    glBufferData(GL_ARRAY_BUFFER, 2 * half, nullptr, GL_STREAM_DRAW);
    glBufferSubData(GL_ARRAY_BUFFER, 0, half, bench.skinned_positions(i).data());
    glBufferSubData(GL_ARRAY_BUFFER, half, half, bench.skinned_normals(i).data());
    counters.bytes_uploaded += vertex_bytes_per_copy(k);
    shown_storage_ = bench.storage_of(i);
    shown_buffer_ = buffer;
  }
  glBindVertexBuffer(0, buffer, 0, sizeof(glm::vec3));
  glBindVertexBuffer(1, buffer, half, sizeof(glm::vec3));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, kind.indices);  // part of the VAO: the copy's character's
  glUniformMatrix4fv(cpu_model_, 1, GL_FALSE, glm::value_ptr(bench.crowd().world[i]));
  glUniform3fv(cpu_colour_, 1, glm::value_ptr(kPalette[i % kPalette.size()]));
  glDrawElements(GL_TRIANGLES, kind.index_count, GL_UNSIGNED_INT, nullptr);
  ++counters.draw_calls;
}

void GlCrowdRenderer::draw_copy_packed(const CrowdBench& bench, size_t i, size_t drawn, Counters& counters) {
  size_t k = bench.crowd().kind[i];
  const Kind& kind = kinds_[k];
  auto positions = static_cast<GLsizeiptr>(kind.vertices * kPackedPositionBytes);
  auto normals = static_cast<GLsizeiptr>(kind.vertices * kPackedNormalBytes);
  GLuint buffer = stream_[drawn % stream_.size()];
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  // Normals start on a 4-byte boundary: the words are read whole.
  GLintptr normals_at = (positions + 3) / 4 * 4;
  glBufferData(GL_ARRAY_BUFFER, normals_at + normals, nullptr, GL_STREAM_DRAW);  // orphaned, as above
  glBufferSubData(GL_ARRAY_BUFFER, 0, positions, bench.packed_positions(i).data());
  glBufferSubData(GL_ARRAY_BUFFER, normals_at, normals, bench.packed_normals(i).data());
  glBindVertexBuffer(0, buffer, 0, static_cast<GLsizei>(kPackedPositionBytes));
  glBindVertexBuffer(1, buffer, normals_at, static_cast<GLsizei>(kPackedNormalBytes));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, kind.indices);
  const PositionQuantisation& q = bench.character_quantisation(k);
  glUniform3fv(packed_min_, 1, glm::value_ptr(q.min));
  glUniform3fv(packed_extent_, 1, glm::value_ptr(q.extent));
  glUniformMatrix4fv(packed_model_, 1, GL_FALSE, glm::value_ptr(bench.crowd().world[i]));
  glUniform3fv(packed_colour_, 1, glm::value_ptr(kPalette[i % kPalette.size()]));
  glDrawElements(GL_TRIANGLES, kind.index_count, GL_UNSIGNED_INT, nullptr);
  counters.bytes_uploaded += kind.vertices * kPackedVertexBytes + sizeof(glm::mat4);
  ++counters.draw_calls;
}

void GlCrowdRenderer::draw_copy_gpu_skinned(const CrowdBench& bench, size_t i, Counters& counters) {
  size_t k = bench.crowd().kind[i];
  const Kind& kind = kinds_[k];
  if (!kind.gpu_vao || kind.joints > max_joints_)
    throw GlError("GPU skinning asked of a renderer whose character is over its bone limit");
  glBindVertexArray(kind.gpu_vao);
  std::span<const SkinMatrix> palette = bench.skinning_matrices(i);
  for (size_t j = 0; j < kind.joints; ++j) put_rows(palette[j], &bone_rows_[3 * j]);
  if (kind.joints > 0)
    glUniform4fv(gpu_bones_, static_cast<GLsizei>(3 * kind.joints), glm::value_ptr(bone_rows_[0]));
  glUniformMatrix4fv(gpu_model_, 1, GL_FALSE, glm::value_ptr(bench.crowd().world[i]));
  glUniform3fv(gpu_colour_, 1, glm::value_ptr(kPalette[i % kPalette.size()]));
  glDrawElements(GL_TRIANGLES, kind.index_count, GL_UNSIGNED_INT, nullptr);
  counters.bytes_uploaded += bone_bytes_per_copy(k);
  ++counters.draw_calls;
}

void GlCrowdRenderer::draw_compute_skinned(const CrowdBench& bench, size_t k, Counters& counters) {
  const Kind& kind = kinds_[k];
  if (!compute_program_.id() || kind.joints > compute_joints_ || kind.vertices > compute_vertices_)
    throw GlError("compute skinning asked of a renderer not prepared for it");
  const Crowd& crowd = bench.crowd();
  batch_copies_.clear();
  for (size_t i = 0; i < crowd.size(); ++i)
    if (bench.visible(i) && crowd.kind[i] == k) batch_copies_.push_back(i);
  auto vertices = static_cast<GLuint>(kind.vertices);
  size_t copy_stride = kind.vertices * 2 * sizeof(glm::vec4);
  for (size_t start = 0; start < batch_copies_.size(); start += compute_batch_) {
    size_t count = std::min(compute_batch_, batch_copies_.size() - start);
    for (size_t c = 0; c < count; ++c) {
      std::span<const SkinMatrix> palette = bench.skinning_matrices(batch_copies_[start + c]);
      for (size_t j = 0; j < kind.joints; ++j) put_rows(palette[j], &compute_rows_[3 * (c * kind.joints + j)]);
    }
    // Fresh storage for both buffers (orphaning): the last batch's draws may still read them.
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, compute_bones_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(compute_batch_ * compute_joints_ * 3 * sizeof(glm::vec4)),
                 nullptr, GL_STREAM_DRAW);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(count * kind.joints * 3 * sizeof(glm::vec4)),
                    compute_rows_.data());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, compute_skinned_);
    glBufferData(GL_SHADER_STORAGE_BUFFER,
                 static_cast<GLsizeiptr>(compute_batch_ * compute_vertices_ * 2 * sizeof(glm::vec4)), nullptr,
                 GL_STREAM_COPY);
    glUseProgram(compute_program_.id());
    glUniform1ui(compute_vertex_count_, vertices);
    glUniform1ui(compute_joint_count_, static_cast<GLuint>(kind.joints));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, kind.rest_storage);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, compute_bones_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, compute_skinned_);
    glDispatchCompute((vertices + kComputeGroup - 1) / kComputeGroup, static_cast<GLuint>(count), 1);
    // The draws below read what the pass wrote as vertex attributes.
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    glUseProgram(cpu_program_.id());
    set_frame_uniforms(cpu_program_, bench);
    glBindVertexArray(compute_vao_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, kind.indices);
    for (size_t c = 0; c < count; ++c) {
      size_t i = batch_copies_[start + c];
      glBindVertexBuffer(0, compute_skinned_, static_cast<GLintptr>(c * copy_stride), 2 * sizeof(glm::vec4));
      glUniformMatrix4fv(cpu_model_, 1, GL_FALSE, glm::value_ptr(crowd.world[i]));
      glUniform3fv(cpu_colour_, 1, glm::value_ptr(kPalette[i % kPalette.size()]));
      glDrawElements(GL_TRIANGLES, kind.index_count, GL_UNSIGNED_INT, nullptr);
      counters.bytes_uploaded += bone_bytes_per_copy(k);
      ++counters.draw_calls;
    }
  }
}

void GlCrowdRenderer::draw_baked(const CrowdBench& bench, Counters& counters) {
  if (!baked_program_.id()) throw GlError("baked skinning asked of a renderer not prepared for it");
  const Crowd& crowd = bench.crowd();
  // This frame's instances, grouped by character: one instanced draw each.
  instance_records_.clear();
  std::vector<size_t>& first = batch_copies_;  // reused: each character's first record, then the end
  first.assign(kinds_.size() + 1, 0);
  for (size_t k = 0; k < kinds_.size(); ++k) {
    first[k] = instance_records_.size();
    if (bench.site_of_kind(k) != SkinningSite::Baked) continue;
    for (size_t i = 0; i < crowd.size(); ++i) {
      if (!bench.visible(i) || crowd.kind[i] != k) continue;
      CrowdBench::BakedInstance b = bench.baked_instance(i);
      instance_records_.push_back({static_cast<uint32_t>(i), b.first_sample, b.intervals, b.position});
    }
  }
  first[kinds_.size()] = instance_records_.size();
  if (instance_records_.empty()) return;
  auto bytes = static_cast<GLsizeiptr>(instance_records_.size() * sizeof(InstanceRecord));
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, instances_);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(instance_capacity_ * sizeof(InstanceRecord)), nullptr,
               GL_STREAM_DRAW);  // orphaned, as the CPU path's buffers
  glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes, instance_records_.data());
  counters.bytes_uploaded += static_cast<uint64_t>(bytes);
  glUseProgram(baked_program_.id());
  set_frame_uniforms(baked_program_, bench);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, placements_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, instances_);
  for (size_t k = 0; k < kinds_.size(); ++k) {
    auto count = static_cast<GLsizei>(first[k + 1] - first[k]);
    if (count == 0) continue;
    const Kind& kind = kinds_[k];
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, kind.baked_table);
    glUniform1ui(baked_joint_count_, static_cast<GLuint>(kind.joints));
    glUniform1ui(baked_first_instance_, static_cast<GLuint>(first[k]));
    glBindVertexArray(kind.gpu_vao);
    glDrawElementsInstanced(GL_TRIANGLES, kind.index_count, GL_UNSIGNED_INT, nullptr, count);
    ++counters.draw_calls;
  }
}

namespace {
// Skinned in the vertex shader from a palette the CPU computed (hwskin, buffer,
// instanced), not by compute or from baked samples.
bool gpu_palette_copy(const CrowdBench& bench, size_t copy) {
  return bench.site_of_kind(bench.crowd().kind[copy]) == SkinningSite::Gpu;
}
}  // namespace

void GlCrowdRenderer::draw_buffer_palettes(const CrowdBench& bench, bool instanced, Counters& counters) {
  require(bench.config().mode);
  const Crowd& crowd = bench.crowd();
  // Room for every copy the GPU skins, so that the frame's buffers never grow
  // while the crowd turns on screen.
  size_t copies = 0, rows = 0;
  std::fill(kind_counts_.begin(), kind_counts_.end(), 0);
  for (size_t i = 0; i < crowd.size(); ++i) {
    if (!gpu_palette_copy(bench, i)) continue;
    ++copies;
    rows += 3 * kinds_[crowd.kind[i]].joints;
    kind_counts_[crowd.kind[i]] += bench.visible(i);
  }
  frame_buffers_.reserve(copies, rows, features_.max_storage_block_bytes);
  frame_buffers_.begin(kind_counts_);
  for (size_t i = 0; i < crowd.size(); ++i) {
    if (!bench.visible(i) || !gpu_palette_copy(bench, i)) continue;
    size_t k = crowd.kind[i];
    std::span<const SkinMatrix> palette = bench.skinning_matrices(i);
    std::span<glm::vec4> out = frame_buffers_.add(k, crowd.world[i], static_cast<uint32_t>(i % kPalette.size()),
                                                   3 * kinds_[k].joints);
    // The 3x4 upper part of each column-major matrix, as rows (as the uniforms).
    for (size_t j = 0; j < kinds_[k].joints; ++j)
      for (int r = 0; r < 3; ++r) {
        const SkinMatrix& m = palette[j];
        out[3 * j + static_cast<size_t>(r)] = glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
      }
  }
  uint64_t sent = frame_buffers_.upload(instanced);
  if (instanced) {
    glUseProgram(instanced_program_.id());
    set_frame_uniforms(instanced_program_, bench);
    glUniform3fv(instanced_program_.uniform("colours"), static_cast<GLsizei>(kPalette.size()),
                 glm::value_ptr(kPalette[0]));
    for (size_t k = 0; k < kinds_.size(); ++k) {
      InstanceRun run = frame_buffers_.run(k);
      if (run.count == 0) continue;
      glBindVertexArray(kinds_[k].instanced_vao);
      glBindVertexBuffer(kInstanceStream, frame_buffers_.instance_buffer(),
                         static_cast<GLintptr>(run.first) * static_cast<GLintptr>(sizeof(GpuInstance)), sizeof(GpuInstance));
      glDrawElementsInstanced(GL_TRIANGLES, kinds_[k].index_count, GL_UNSIGNED_INT, nullptr,
                              static_cast<GLsizei>(run.count));
      ++counters.draw_calls;
    }
    counters.bytes_uploaded += sent;
    counters.gpu_palette_bytes = frame_buffers_.gpu_bytes();
    return;
  }
  glUseProgram(buffer_program_.id());
  set_frame_uniforms(buffer_program_, bench);
  std::vector<uint32_t>& next = kind_counts_;  // per kind, the next record to draw
  for (size_t k = 0; k < kinds_.size(); ++k) next[k] = frame_buffers_.run(k).first;
  for (size_t i = 0; i < crowd.size(); ++i) {
    if (!bench.visible(i) || !gpu_palette_copy(bench, i)) continue;
    size_t k = crowd.kind[i];
    glBindVertexArray(kinds_[k].gpu_vao);
    glUniform1ui(buffer_base_, frame_buffers_.palette_base(next[k]++));
    glUniformMatrix4fv(buffer_model_, 1, GL_FALSE, glm::value_ptr(crowd.world[i]));
    glUniform3fv(buffer_colour_, 1, glm::value_ptr(kPalette[i % kPalette.size()]));
    glDrawElements(GL_TRIANGLES, kinds_[k].index_count, GL_UNSIGNED_INT, nullptr);
    counters.bytes_uploaded += sizeof(glm::mat4);  // the model matrix; the palette went in `sent`
    ++counters.draw_calls;
  }
  counters.bytes_uploaded += sent;
  counters.gpu_palette_bytes = frame_buffers_.palette_gpu_bytes();
}

void GlCrowdRenderer::finish() {
  glFinish();
  check_gl("GPU Latency");
}

std::string GlCrowdRenderer::gpu_timing_missing() const {
  if (features_.timer_queries()) return {};
  return context_.renderer() + " has no GL_TIME_ELAPSED timer (0 counter bits)";
}

size_t GlCrowdRenderer::take_gpu_times(const CrowdBench& owner, uint64_t frame, std::span<GpuTime> out, bool wait) {
  if (!features_.timer_queries()) return 0;
  size_t taken = timer_.take(&owner, frame, out, wait);
  check_gl("Overhead (reading GPU timer queries)");
  return taken;
}

}  // namespace crowdprof

#include "render/gpu_frame_buffers.h"

#include <algorithm>
#include <string>

#include "render/gl_errors.h"

namespace crowdprof {

namespace {

std::string mib(uint64_t bytes) {
  return std::to_string(bytes >> 20) + "." + std::to_string(((bytes & ((1u << 20) - 1)) * 10) >> 20) + " MiB";
}

}  // namespace

GpuFrameBuffers::~GpuFrameBuffers() {
  glDeleteBuffers(1, &palette_buffer_);
  glDeleteBuffers(1, &instance_buffer_);
}

void GpuFrameBuffers::reserve(size_t instances, size_t rows, int64_t max_block_bytes) {
  uint64_t palette_bytes = std::max<uint64_t>(rows, 1) * sizeof(glm::vec4);
  uint64_t instance_bytes = std::max<uint64_t>(instances, 1) * sizeof(GpuInstance);
  if (palette_bytes > static_cast<uint64_t>(max_block_bytes) || instance_bytes > static_cast<uint64_t>(max_block_bytes))
    throw GlUnavailable("the palettes of this crowd need " + mib(std::max(palette_bytes, instance_bytes)) +
                            " in one shader storage buffer; this GL allows " +
                            mib(static_cast<uint64_t>(max_block_bytes)) + " (GL_MAX_SHADER_STORAGE_BLOCK_SIZE): ",
                        "use fewer copies or {palettes} uniforms");
  if (instances > instances_.size()) instances_.resize(instances);
  if (rows > rows_.size()) rows_.resize(rows);
  if (!palette_buffer_) glGenBuffers(1, &palette_buffer_);
  if (!instance_buffer_) glGenBuffers(1, &instance_buffer_);
  palette_capacity_bytes_ = std::max(palette_capacity_bytes_, palette_bytes);
  instance_capacity_bytes_ = std::max(instance_capacity_bytes_, instance_bytes);
}

void GpuFrameBuffers::begin(std::span<const uint32_t> counts) {
  runs_.assign(counts.size(), InstanceRun{});
  filled_.assign(counts.size(), 0);
  uint32_t first = 0;
  for (size_t k = 0; k < counts.size(); ++k) {
    runs_[k] = {first, counts[k]};
    first += counts[k];
  }
  rows_used_ = 0;
}

std::span<glm::vec4> GpuFrameBuffers::add(size_t kind, const glm::mat4& model, uint32_t colour, size_t palette_rows) {
  GpuInstance& record = instances_[runs_[kind].first + filled_[kind]++];
  record.model = model;
  record.colour = colour;
  record.palette_base = static_cast<uint32_t>(rows_used_);
  std::span<glm::vec4> rows = std::span(rows_).subspan(rows_used_, palette_rows);
  rows_used_ += palette_rows;
  return rows;
}

uint64_t GpuFrameBuffers::upload(bool with_instances) {
  uint64_t sent = rows_used_ * sizeof(glm::vec4);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, palette_buffer_);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(palette_capacity_bytes_), nullptr, GL_STREAM_DRAW);
  if (rows_used_) glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(sent), rows_.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPaletteBinding, palette_buffer_);
  if (with_instances) {
    uint32_t records = 0;
    for (const InstanceRun& run : runs_) records += run.count;
    uint64_t bytes = uint64_t{records} * sizeof(GpuInstance);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, instance_buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(instance_capacity_bytes_), nullptr, GL_STREAM_DRAW);
    if (records) glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), instances_.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstanceBinding, instance_buffer_);
    sent += bytes;
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return sent;
}

}  // namespace crowdprof

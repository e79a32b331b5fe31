#include "render/gpu_frame_buffers.h"

#include <algorithm>
#include <bit>
#include <string>

#include "render/gl_errors.h"

namespace crowdprof {

namespace {

// "3.2 MiB", or "64.0 KiB" below a MiB.
std::string mib(uint64_t bytes) {
  const int shift = bytes < (uint64_t{1} << 20) ? 10 : 20;
  const uint64_t unit = uint64_t{1} << shift;
  return std::to_string(bytes >> shift) + "." + std::to_string((bytes & (unit - 1)) * 10 >> shift) +
         (shift == 10 ? " KiB" : " MiB");
}

}  // namespace

GpuFrameBuffers::~GpuFrameBuffers() {
  glDeleteBuffers(1, &palette_buffer_);
  glDeleteBuffers(1, &instance_buffer_);
}

void GpuFrameBuffers::reserve(size_t instances, size_t rows, size_t largest_rows, bool with_instances,
                              const GlFeatures& gl) {
  const auto block = static_cast<uint64_t>(std::max<int64_t>(gl.max_storage_block_bytes, 0));
  const auto align = static_cast<uint64_t>(std::max<int64_t>(gl.storage_offset_alignment, 1));
  page_rows_ = block / align * align / sizeof(glm::vec4);
  if (largest_rows > 0 && (page_rows_ == 0 || largest_rows > page_rows_))
    throw GlUnavailable("a palette of " + std::to_string(largest_rows / 3) + " joints needs " +
                            mib(largest_rows * sizeof(glm::vec4)) + "; a page of this GL's palette buffer holds " +
                            mib(page_rows_ * sizeof(glm::vec4)) +
                            " (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, on GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT): ",
                        "skin it on the CPU, {skinning} animations");
  // The records are read as per-instance vertex attributes (instanced and
  // baked), which no storage-block limit bounds.
  const uint64_t instance_bytes = with_instances ? std::max<uint64_t>(instances, 1) * sizeof(GpuInstance) : 0;
  // In one page, the rows themselves; past it, a page leaves less than its
  // largest palette empty at its end.
  const uint64_t pages =
      page_rows_ > largest_rows ? rows / (page_rows_ - largest_rows) + 1 : std::max<size_t>(instances, 1);
  const uint64_t palette_rows =
      rows <= page_rows_ ? rows : std::min<uint64_t>(rows + pages * largest_rows, pages * page_rows_);
  // Records only (another skinning source's): no palette buffer.
  const uint64_t palette_bytes = largest_rows == 0 ? 0 : std::max<uint64_t>(palette_rows, 1) * sizeof(glm::vec4);
  if (gl.memory_free_kib >= 0 && instances > 0) {
    const uint64_t free_bytes = static_cast<uint64_t>(gl.memory_free_kib) << 10;
    const uint64_t per_copy = (rows + instances - 1) / instances * sizeof(glm::vec4) + instance_bytes / instances;
    if (palette_bytes + instance_bytes > free_bytes)
      throw GlUnavailable(std::string(with_instances ? "the palettes and instance records of " : "the palettes of ") +
                              std::to_string(instances) + " copies need " + mib(palette_bytes + instance_bytes) +
                              "; the GPU has " + mib(free_bytes) + " free (" + gl.memory_source + "), room for about " +
                              std::to_string(free_bytes / per_copy) + " copies: ",
                          "use fewer copies");
  }
  if (instances > instances_.size()) instances_.resize(instances);
  if (instances > page_of_.size()) page_of_.resize(instances);
  if (instances > placement_page_of_.size()) placement_page_of_.resize(instances);
  placement_page_copies_ = GpuPlacements::copies_per_page(gl);
  if (palette_bytes / sizeof(glm::vec4) > rows_.size()) rows_.resize(palette_bytes / sizeof(glm::vec4));
  if (!palette_buffer_) glGenBuffers(1, &palette_buffer_);
  if (!instance_buffer_) glGenBuffers(1, &instance_buffer_);
  palette_capacity_bytes_ = std::max(palette_capacity_bytes_, palette_bytes);
  grow_instance_storage(instance_bytes);
}

void GpuFrameBuffers::reserve_gpu_records(size_t records, const GlFeatures& gl) {
  const uint64_t bytes = std::max<uint64_t>(records, 1) * sizeof(GpuInstance);
  if (gl.memory_free_kib >= 0 && bytes > static_cast<uint64_t>(gl.memory_free_kib) << 10) {
    const uint64_t free_bytes = static_cast<uint64_t>(gl.memory_free_kib) << 10;
    throw GlUnavailable(std::to_string(records) + " instance records need " + mib(bytes) + "; the GPU has " +
                            mib(free_bytes) + " free (" + gl.memory_source + "), room for about " +
                            std::to_string(free_bytes / sizeof(GpuInstance)) + ": ",
                        "use fewer copies");
  }
  if (!instance_buffer_) glGenBuffers(1, &instance_buffer_);
  grow_instance_storage(bytes);
}

void GpuFrameBuffers::grow_instance_storage(uint64_t bytes) {
  if (bytes <= instance_capacity_bytes_) return;
  // Storage now, for a compute pass that writes the records (upload() orphans it each frame).
  instance_capacity_bytes_ = bytes;
  glBindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(instance_capacity_bytes_), nullptr, GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
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

std::span<glm::vec4> GpuFrameBuffers::add(size_t kind, uint32_t copy, size_t palette_rows) {
  const uint32_t index = runs_[kind].first + filled_[kind]++;
  GpuInstance& record = instances_[index];
  record.copy = static_cast<uint32_t>(copy % placement_page_copies_);
  placement_page_of_[index] = static_cast<uint32_t>(copy / placement_page_copies_);
  if (palette_rows > page_rows_) throw GlError("a palette larger than a storage block asked of the palette buffer");
  // A palette that would cross into the next page starts it.
  size_t page = rows_used_ / page_rows_;
  if (rows_used_ % page_rows_ + palette_rows > page_rows_) rows_used_ = ++page * page_rows_;
  record.palette_base = static_cast<uint32_t>(rows_used_ - page * page_rows_);
  page_of_[index] = static_cast<uint32_t>(page);
  // Mixed characters may leave more at a page's end than reserve() allowed for.
  if (rows_used_ + palette_rows > rows_.size()) rows_.resize(std::max(rows_used_ + palette_rows, rows_.size() * 5 / 4));
  std::span<glm::vec4> rows = std::span(rows_).subspan(rows_used_, palette_rows);
  rows_used_ += palette_rows;
  return rows;
}

void GpuFrameBuffers::add_record(size_t kind, const GpuInstance& record) {
  const uint32_t index = runs_[kind].first + filled_[kind]++;
  instances_[index] = record;
  instances_[index].copy = static_cast<uint32_t>(record.copy % placement_page_copies_);
  page_of_[index] = 0;
  placement_page_of_[index] = static_cast<uint32_t>(record.copy / placement_page_copies_);
}

void GpuFrameBuffers::add_fading_record(size_t kind, const GpuInstance& record, const GpuFade& fade) {
  add_record(kind, record);
  // The fade's slot, on the record's pages: a page's run never splits the two.
  const uint32_t index = runs_[kind].first + filled_[kind]++;
  instances_[index] = std::bit_cast<GpuInstance>(fade);
  page_of_[index] = page_of_[index - 1];
  placement_page_of_[index] = placement_page_of_[index - 1];
}

InstanceRun GpuFrameBuffers::page_run(size_t kind, uint32_t from) const {
  const uint32_t end = runs_[kind].first + runs_[kind].count;
  uint32_t last = from;
  while (last < end && page_of_[last] == page_of_[from] && placement_page_of_[last] == placement_page_of_[from]) ++last;
  return {from, last - from};
}

void GpuFrameBuffers::bind_page(uint32_t page) const {
  if (palette_capacity_bytes_ == 0) return;  // records only
  const uint64_t page_bytes = page_rows_ * sizeof(glm::vec4);
  const uint64_t offset = page * page_bytes;
  const uint64_t size = std::min(page_bytes, palette_capacity_bytes_ - offset);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kPaletteBinding, palette_buffer_, static_cast<GLintptr>(offset),
                    static_cast<GLsizeiptr>(size));
}

SentBytes GpuFrameBuffers::upload(bool with_instances) {
  // The rows left empty at pages' ends go up too (one upload).
  SentBytes sent{rows_used_ * sizeof(glm::vec4), 0};
  palette_capacity_bytes_ = std::max(palette_capacity_bytes_, sent.palettes);
  if (palette_capacity_bytes_ > 0) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, palette_buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(palette_capacity_bytes_), nullptr, GL_STREAM_DRAW);
    if (rows_used_) glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(sent.palettes), rows_.data());
    bind_page(0);
  }
  if (with_instances) {
    uint32_t records = 0;
    for (const InstanceRun& run : runs_) records += run.count;
    uint64_t bytes = uint64_t{records} * sizeof(GpuInstance);
    glBindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(instance_capacity_bytes_), nullptr, GL_STREAM_DRAW);
    if (records) glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), instances_.data());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    sent.records = bytes;
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return sent;
}

}  // namespace crowdprof

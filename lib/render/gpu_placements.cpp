#include "render/gpu_placements.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <string>

#include "frame/frame_view.h"
#include "render/gl_errors.h"
#include "render/shader_sources.h"
#include "render/techniques/technique.h"

namespace crowdprof {

namespace {

bool same(const GpuPlacement& a, const GpuPlacement& b) {
  return std::memcmp(&a, &b, sizeof(GpuPlacement)) == 0;
}

}  // namespace

GpuPlacements::~GpuPlacements() {
  glDeleteBuffers(1, &buffer_);
}

uint64_t GpuPlacements::update(const FrameView& view, const GlFeatures& gl) {
  const size_t copies = std::max<size_t>(view.copies(), 1);  // a buffer to bind, even for no copy
  page_copies_ = copies_per_page(gl);
  now_.assign(copies, GpuPlacement{});
  for (size_t i = 0; i < view.copies(); ++i) {
    const glm::mat4& m = view.world[i];
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f)
      throw GlError("copy " + std::to_string(i) + "'s placement is not affine: its fourth row would be lost");
    for (int r = 0; r < 3; ++r) now_[i].rows[r] = glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
  }
  if (!buffer_) glGenBuffers(1, &buffer_);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer_);
  uint64_t sent = 0;
  if (sent_.size() != copies) {
    sent = copies * sizeof(GpuPlacement);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(sent), now_.data(), GL_STATIC_DRAW);
  } else {
    // Each run of copies whose placement changed, in one call.
    for (size_t i = 0; i < copies;) {
      if (same(now_[i], sent_[i])) {
        ++i;
        continue;
      }
      size_t end = i + 1;
      while (end < copies && !same(now_[end], sent_[end])) ++end;
      const uint64_t bytes = (end - i) * sizeof(GpuPlacement);
      glBufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(i * sizeof(GpuPlacement)),
                      static_cast<GLsizeiptr>(bytes), &now_[i]);
      sent += bytes;
      i = end;
    }
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (sent) sent_.swap(now_);
  return sent;
}

size_t GpuPlacements::copies_per_page(const GlFeatures& gl) {
  const auto block = static_cast<uint64_t>(std::max<int64_t>(gl.max_uniform_block_bytes, 0));
  const auto align = static_cast<uint64_t>(std::max<int64_t>(gl.uniform_offset_alignment, 1));
  // Copies from one offset a range may start at to the next, and whole
  // cycles of the colours: a copy's colour follows from its index in its page.
  const uint64_t step =
      std::lcm(align / std::gcd(align, uint64_t{sizeof(GpuPlacement)}), uint64_t{kCopyColours.size()});
  return std::max<uint64_t>(block / sizeof(GpuPlacement) / step * step, step);
}

std::string GpuPlacements::shader_source(PlacementBlock block, const GlFeatures& gl) {
  const std::string define = block == PlacementBlock::Storage
                                 ? "#define PLACEMENTS_IN_STORAGE\n"
                                 : "#define PLACEMENT_ROWS " + std::to_string(3 * copies_per_page(gl)) + "\n";
  return define + std::string(embedded_shader("shaders/placements.glsl"));
}

void GpuPlacements::bind_page(uint32_t page) const {
  const uint64_t page_bytes = page_copies_ * sizeof(GpuPlacement);
  const uint64_t offset = page * page_bytes;
  const uint64_t size = std::min(page_bytes, gpu_bytes() - offset);
  glBindBufferRange(GL_UNIFORM_BUFFER, kPlacementBinding, buffer_, static_cast<GLintptr>(offset),
                    static_cast<GLsizeiptr>(size));
}

void GpuPlacements::bind_storage() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPlacementBinding, buffer_);
}

}  // namespace crowdprof

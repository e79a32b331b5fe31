#include "render/gl_features.h"

#include <algorithm>
#include <cstdlib>

#include "base/errors.h"
#include "render/gl.h"

namespace crowdprof {

GlFeatures read_gl_features(std::string_view hide) {
  GlFeatures f;
  GLint value = 0;
  glGetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &value);
  f.vertex_storage_blocks = value;
  GLint64 bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
  f.max_storage_block_bytes = bytes;
  value = 0;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &value);
  if (value > 0) f.storage_offset_alignment = value;
  bytes = 0;
  glGetInteger64v(GL_MAX_UNIFORM_BLOCK_SIZE, &bytes);
  if (bytes > 0) f.max_uniform_block_bytes = bytes;
  value = 0;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &value);
  if (value > 0) f.uniform_offset_alignment = value;
  value = 0;
  glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &value);
  f.compute_storage_blocks = value;
  value = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &value);
  f.timer_bits = value;
  GLint extensions = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &extensions);
  for (GLint e = 0; e < extensions; ++e) {
    const auto* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(e)));
    if (!name) continue;
    std::string_view ext(name);
    if (ext == "GL_ARB_pipeline_statistics_query") f.pipeline_statistics = true;
    if (ext == "GL_NVX_gpu_memory_info") {
      GLint total = 0, free = 0;
      glGetIntegerv(0x9048 /* GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX */, &total);
      glGetIntegerv(0x9049 /* GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX */, &free);
      f.memory_total_kib = total;
      f.memory_free_kib = free;
      f.memory_source = "NVX_gpu_memory_info";
    } else if (ext == "GL_ATI_meminfo" && f.memory_source == "unknown") {
      GLint free[4] = {0, 0, 0, 0};  // total free, largest block, auxiliary free, largest
      glGetIntegerv(0x87FB /* VBO_FREE_MEMORY_ATI */, free);
      f.memory_free_kib = free[0];
      f.memory_source = "ATI_meminfo";
    }
  }
  glGetError();  // a GL without one of these may flag the query; absence is the answer
  while (!hide.empty()) {
    size_t comma = hide.find(',');
    std::string_view name = hide.substr(0, comma);
    hide = comma == std::string_view::npos ? std::string_view{} : hide.substr(comma + 1);
    while (!name.empty() && name.front() == ' ') name.remove_prefix(1);
    while (!name.empty() && name.back() == ' ') name.remove_suffix(1);
    if (name == "vertex-ssbo")
      f.vertex_storage_blocks = 0;
    else if (name == "timer-query")
      f.timer_bits = 0;
    else if (name == "compute")
      f.compute_storage_blocks = 0;
    else if (name == "pipeline-statistics")
      f.pipeline_statistics = false;
    else if (name == "small-blocks")
      f.max_storage_block_bytes = std::min<int64_t>(f.max_storage_block_bytes, int64_t{64} << 10);
    else if (!name.empty())
      throw UsageError("CROWDPROF_GL_HIDE '" + std::string(name) + "': expected some of " +
                       std::string(kHideableGlFeatures));
  }
  return f;
}

std::string gl_hide_from_environment() {
  const char* hide = std::getenv("CROWDPROF_GL_HIDE");
  return hide ? hide : "";
}

}  // namespace crowdprof

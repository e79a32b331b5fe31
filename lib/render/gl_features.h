// What the current GL context offers beyond the 4.3 core that every context
// has: the features some modes need, read once, so that a mode that needs one
// the context lacks is refused in one line (exit 4) before its first frame,
// never drawn as a black image.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace crowdprof {

struct GlFeatures {
  // Shader storage blocks a vertex shader may read: 4.3 requires none in the
  // vertex stage (only fragment and compute), so a context may offer 0.
  int64_t vertex_storage_blocks = 0;
  int64_t max_storage_block_bytes = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  // GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT: where a bound range may start.
  int64_t storage_offset_alignment = 256;
  // GL_MAX_UNIFORM_BLOCK_SIZE (4.3 promises 16 KiB) and
  // GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT: the placements' pages (gpu_placements.h).
  int64_t max_uniform_block_bytes = 16384;
  int64_t uniform_offset_alignment = 256;
  // Shader storage blocks a compute shader may use (skinning compute); 0 means
  // no compute shaders to speak of.
  int64_t compute_storage_blocks = 0;
  // Bits of GL_TIME_ELAPSED's counter; 0 means timer queries do not work.
  int64_t timer_bits = 0;
  // ARB_pipeline_statistics_query (core in 4.6): vertices, primitives and
  // shader invocations per pass.
  bool pipeline_statistics = false;
  // The GPU's memory in KiB, where NVX_gpu_memory_info or ATI_meminfo says
  // (-1: not said); memory_source names which.
  int64_t memory_total_kib = -1, memory_free_kib = -1;
  std::string memory_source = "unknown";

  bool storage_buffers() const { return vertex_storage_blocks > 0 && max_storage_block_bytes > 0; }
  bool timer_queries() const { return timer_bits > 0; }
};

// The names `hide` understands, comma-separated: "vertex-ssbo", "timer-query",
// "compute".
// "small-blocks" is not a feature but a limit: storage blocks of 64 KiB, so that
// a small crowd's palettes take several pages (tests of the paging).
inline constexpr std::string_view kHideableGlFeatures =
    "vertex-ssbo, timer-query, compute, pipeline-statistics, small-blocks";

// Reads the current context's features, then acts as if it lacked those that
// `hide` names (CROWDPROF_GL_HIDE: to see what crowdprof does on a GL without
// them). Throws UsageError for a name it does not know.
GlFeatures read_gl_features(std::string_view hide = {});

// What `hide` comes from in a run: the CROWDPROF_GL_HIDE environment variable.
std::string gl_hide_from_environment();

}  // namespace crowdprof

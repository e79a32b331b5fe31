#include "render/gl_features.h"

#include <cstdlib>

#include "asset/errors.h"
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
  glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &value);
  f.compute_storage_blocks = value;
  value = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &value);
  f.timer_bits = value;
  GLint extensions = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &extensions);
  for (GLint e = 0; e < extensions; ++e) {
    const auto* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(e)));
    if (name && std::string_view(name) == "GL_ARB_pipeline_statistics_query") f.pipeline_statistics = true;
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

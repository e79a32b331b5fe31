#include "render/techniques/technique.h"

#include <glm/gtc/type_ptr.hpp>

#include "frame/frame_view.h"
#include "render/shader_sources.h"
#include "scene/shadow_cascades.h"

namespace crowdprof {

GLuint make_buffer(GLenum target, size_t bytes, const void* data, GLenum usage) {
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(target, buffer);
  glBufferData(target, static_cast<GLsizeiptr>(bytes), data, usage);
  return buffer;
}

void put_rows(const SkinMatrix& m, glm::vec4* rows) {
  for (int r = 0; r < 3; ++r) rows[r] = glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
}

std::vector<ShaderStage> lit_stages(const char* vertex, const std::string& defines,
                                    const std::string& fragment_defines) {
  return {
      {GL_VERTEX_SHADER, vertex, with_defines(embedded_shader(vertex), defines)},
      {GL_FRAGMENT_SHADER, "shaders/lit.frag", with_defines(embedded_shader("shaders/lit.frag"), fragment_defines)}};
}

void set_frame_uniforms(const GlProgram& program, const DrawPass& pass) {
  glUniformMatrix4fv(program.uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(pass.view_projection));
  glUniform3fv(program.uniform("light_direction"), 1, glm::value_ptr(kLightDirection));
}

}  // namespace crowdprof

#include <cstdio>
#include <string>

#include "render/gl.h"
#include "render/gl_errors.h"

namespace crowdprof {

std::string gl_error_name(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    default:
      break;
  }
  char code[32];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(error));
  return code;
}

void check_gl(std::string_view where) {
  GLenum first = glGetError();
  if (first == GL_NO_ERROR) return;
  // GL keeps one flag per kind of error: drain them so the next check starts clean.
  for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {
  }
  throw GlError("GL error " + gl_error_name(first) + " during " + std::string(where));
}

}  // namespace crowdprof

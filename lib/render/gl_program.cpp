#include "render/gl_program.h"

#include <algorithm>
#include <cctype>
#include <utility>

#include "render/gl_errors.h"

namespace crowdprof {

std::string with_defines(std::string_view source, std::string_view defines) {
  size_t version = source.find("#version");
  if (version == std::string_view::npos) return std::string(defines) + "#line 1\n" + std::string(source);
  size_t end = source.find('\n', version);
  if (end == std::string_view::npos) end = source.size() - 1;
  int version_line = 1;
  for (size_t i = 0; i < end; ++i) version_line += source[i] == '\n';
  // GLSL 3.30 and later: the line after "#line N" is line N.
  return std::string(source.substr(0, end + 1)) + std::string(defines) + "#line " + std::to_string(version_line + 1) +
         "\n" + std::string(source.substr(end + 1));
}

int first_log_line(std::string_view log) {
  // Each message starts "<source>:<line>(" (Mesa) or "<source>(<line>)" (NVIDIA).
  size_t start = 0;
  while (start < log.size()) {
    size_t i = start;
    while (i < log.size() && std::isdigit(static_cast<unsigned char>(log[i]))) ++i;
    if (i > start && i < log.size() && (log[i] == ':' || log[i] == '(')) {
      size_t j = ++i;
      int line = 0;
      while (j < log.size() && std::isdigit(static_cast<unsigned char>(log[j])) && line < 1'000'000)
        line = line * 10 + (log[j++] - '0');
      if (j > i) return line;
    }
    size_t next = log.find('\n', start);
    if (next == std::string_view::npos) break;
    start = next + 1;
  }
  return 0;
}

namespace {

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return std::string(log.c_str());
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return std::string(log.c_str());
}

}  // namespace

GLuint build_program(std::span<const ShaderStage> stages) {
  GLuint program = glCreateProgram();
  std::string names;
  for (const ShaderStage& stage : stages) {
    names += (names.empty() ? "" : ", ") + stage.name;
    GLuint shader = glCreateShader(stage.type);
    const char* text = stage.text.c_str();
    GLint length = static_cast<GLint>(stage.text.size());
    glShaderSource(shader, 1, &text, &length);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      std::string log = shader_log(shader);
      glDeleteShader(shader);
      glDeleteProgram(program);
      int line = first_log_line(log);
      throw GlError(stage.name + (line > 0 ? ":" + std::to_string(line) : "") + ": does not compile:\n" + log);
    }
    glAttachShader(program, shader);
    glDeleteShader(shader);  // freed with the program
  }
  glLinkProgram(program);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    std::string log = program_log(program);
    glDeleteProgram(program);
    throw GlError(names + ": do not link:\n" + log);
  }
  check_gl("shader compilation");
  return program;
}

GlProgram::~GlProgram() {
  if (id_) glDeleteProgram(id_);
}

GlProgram& GlProgram::operator=(GlProgram&& other) noexcept {
  std::swap(id_, other.id_);
  return *this;
}

GLint GlProgram::uniform(const char* name) const {
  GLint location = glGetUniformLocation(id_, name);
  if (location < 0) throw GlError(std::string("shader program has no uniform '") + name + "'");
  return location;
}

}  // namespace crowdprof

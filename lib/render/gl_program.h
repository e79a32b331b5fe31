// Shader programs from the embedded shaders/ files, with errors that name the
// file and the line and carry the driver's log.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "render/gl.h"

namespace crowdprof {

struct ShaderStage {
  GLenum type = GL_VERTEX_SHADER;  // or GL_FRAGMENT_SHADER
  std::string name;                // for messages: "shaders/hwskin.vert"
  std::string text;
};

// `source` with `defines` ("#define MAX_BONES 128\n") inserted after its
// #version line, and a #line directive so the driver's line numbers still
// match the file.
std::string with_defines(std::string_view source, std::string_view defines);

// The first line number in a driver's compile log ("0:12(5): error: ..." from
// Mesa, "0(12) : error ..." from NVIDIA), or 0 when it names none.
int first_log_line(std::string_view log);

// Compiles and links the stages into a program (needs a current context).
// Throws GlError: "shaders/hwskin.vert:12: does not compile: <log>", or for a
// link failure the names of all stages and the log.
GLuint build_program(std::span<const ShaderStage> stages);

// A program and the GL object's lifetime.
class GlProgram {
 public:
  GlProgram() = default;
  explicit GlProgram(std::span<const ShaderStage> stages) : id_(build_program(stages)) {}
  ~GlProgram();
  GlProgram(GlProgram&& other) noexcept : id_(other.id_) { other.id_ = 0; }
  GlProgram& operator=(GlProgram&& other) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return id_; }
  // Throws GlError when the program has no active uniform of that name.
  GLint uniform(const char* name) const;

 private:
  GLuint id_ = 0;
};

}  // namespace crowdprof

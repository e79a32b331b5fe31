// What can go wrong with GL, as exceptions the CLI turns into one line on
// stderr and exit 4 (base/errors.h): the run itself failed.
#pragma once

#include <stdexcept>
#include <string>

#include "base/errors.h"

namespace crowdprof {

// No usable GL: no EGL display or OSMesa, or no OpenGL 4.3 core context, or
// a feature a mode needs. With a SettingText, the text ends naming the
// setting that would do without it.
class GlUnavailable : public std::runtime_error, public NamesSettings {
 public:
  explicit GlUnavailable(const std::string& literal) : std::runtime_error(literal), NamesSettings(literal, {}) {}
  GlUnavailable(const std::string& literal, const SettingText& text)
      : std::runtime_error(literal + text.str()), NamesSettings(literal, text) {}
};

// A GL error during a frame (names the error and the stage), a shader that does
// not compile or link (names the file, the line, and has the driver's log), an
// incomplete framebuffer.
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace crowdprof

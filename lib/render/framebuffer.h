// The off-screen image a frame is drawn into: a framebuffer object with an
// RGBA8 colour and a 24-bit depth renderbuffer, of the --resolution size.
#pragma once

#include <cstdint>
#include <vector>

#include "render/gl.h"

namespace crowdprof {

class Framebuffer {
 public:
  // Needs a current context. Throws UsageError for a size of 0 or past what the
  // GL allows (GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS), GlError when the
  // driver cannot complete it.
  Framebuffer(int width, int height);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  // Binds it for drawing and sets the viewport to all of it.
  void bind() const;
  int width() const { return width_; }
  int height() const { return height_; }

  // The image, RGBA8, rows from top to bottom (as PNG stores them); waits for
  // the drawing to finish. Throws GlError.
  std::vector<uint8_t> read_rgba() const;

 private:
  void release();

  int width_ = 0, height_ = 0;
  GLuint framebuffer_ = 0, colour_ = 0, depth_ = 0;
};

// The largest width and height this context can render to.
int max_framebuffer_size();

}  // namespace crowdprof

#include "render/framebuffer.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "base/errors.h"
#include "render/gl_errors.h"

namespace crowdprof {

int max_framebuffer_size() {
  GLint renderbuffer = 0, viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  return std::min({renderbuffer, viewport[0], viewport[1]});
}

Framebuffer::Framebuffer(int width, int height) : width_(width), height_(height) {
  int limit = max_framebuffer_size();
  if (width < 1 || height < 1 || width > limit || height > limit)
    throw SettingsUsageError("{resolution} " + std::to_string(width) + "x" + std::to_string(height) +
                             ": this GL renders 1 to " + std::to_string(limit) + " pixels each way");
  glGenFramebuffers(1, &framebuffer_);
  glGenRenderbuffers(1, &colour_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  GLenum error = glGetError();
  if (status != GL_FRAMEBUFFER_COMPLETE || error != GL_NO_ERROR) {
    release();
    throw GlError("cannot make a " + std::to_string(width) + "x" + std::to_string(height) + " framebuffer (" +
                  (error != GL_NO_ERROR ? gl_error_name(error) : "status " + std::to_string(status)) + ")");
  }
}

Framebuffer::~Framebuffer() {
  release();
}

void Framebuffer::release() {
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
  if (colour_) glDeleteRenderbuffers(1, &colour_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  framebuffer_ = colour_ = depth_ = 0;
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width_, height_);
}

std::vector<uint8_t> Framebuffer::read_rgba() const {
  size_t row = static_cast<size_t>(width_) * 4;
  std::vector<uint8_t> pixels(row * static_cast<size_t>(height_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  check_gl("reading the frame back");
  // GL's rows run bottom to top.
  std::vector<uint8_t> swap(row);
  for (size_t top = 0, bottom = static_cast<size_t>(height_) - 1; top < bottom; ++top, --bottom) {
    std::memcpy(swap.data(), &pixels[top * row], row);
    std::memcpy(&pixels[top * row], &pixels[bottom * row], row);
    std::memcpy(&pixels[bottom * row], swap.data(), row);
  }
  return pixels;
}

}  // namespace crowdprof

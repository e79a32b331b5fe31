#include "render/draw_passes.h"

#include <string>

#include "render/gl_errors.h"

namespace crowdprof {

std::vector<DrawPass> draw_passes(const FrameView& view) {
  std::vector<DrawPass> passes;
  if (view.mode.passes >= 2) passes.push_back({GpuPass::Prepass, view.view_projection, 0});
  for (size_t c = 0; c < view.shadow_view_projections.size(); ++c)
    passes.push_back({GpuPass::Shadows, view.shadow_view_projections[c], c});
  passes.push_back({GpuPass::Colour, view.view_projection, 0});
  return passes;
}

ShadowMaps::~ShadowMaps() {
  glDeleteFramebuffers(static_cast<GLsizei>(framebuffers_.size()), framebuffers_.data());
  glDeleteTextures(static_cast<GLsizei>(textures_.size()), textures_.data());
}

void ShadowMaps::reserve(size_t count) {
  while (framebuffers_.size() < count) {
    GLuint texture = 0, framebuffer = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, kSize, kSize);
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, texture, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    textures_.push_back(texture);
    framebuffers_.push_back(framebuffer);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("cannot make a " + std::to_string(kSize) + "x" + std::to_string(kSize) +
                    " shadow map (framebuffer status " + std::to_string(status) + ")");
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  check_gl("making shadow maps");
}

void ShadowMaps::bind_and_clear(size_t c) const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffers_.at(c));
  glViewport(0, 0, kSize, kSize);
  glClear(GL_DEPTH_BUFFER_BIT);
}

}  // namespace crowdprof

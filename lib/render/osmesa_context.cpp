// The OSMesa backend: Mesa's off-screen renderer (llvmpipe), which needs no
// display, no device and no EGL. GL/osmesa.h pulls in GL/gl.h, which clashes
// with glad's header, so this file includes nothing of render/gl.h.
#include <GL/osmesa.h>

#include <array>
#include <memory>

#include "render/gl_context.h"
#include "render/gl_errors.h"

namespace crowdprof {

namespace {

GlContext::Proc osmesa_proc(const char* name) { return OSMesaGetProcAddress(name); }

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() : GlContext(GlBackend::OsMesa, "OSMesa") {
    // No depth or stencil in OSMesa's own buffer: crowdprof draws into a
    // framebuffer object that has its own.
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                              OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context_) throw GlUnavailable("OSMesa: no OpenGL 4.3 core context (is libOSMesa built with llvmpipe?)");
    try {
      initialise();
    } catch (...) {
      OSMesaDestroyContext(context_);
      throw;
    }
  }
  ~OsMesaContext() override {
    if (OSMesaGetCurrentContext() == context_) OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(context_);
  }

 protected:
  // OSMesa needs a buffer to make a context current; a pixel is enough.
  bool bind() override { return OSMesaMakeCurrent(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1) == GL_TRUE; }
  Loader loader() const override { return osmesa_proc; }

 private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> pixel_{};
};

}  // namespace

std::unique_ptr<GlContext> create_osmesa_context() { return std::make_unique<OsMesaContext>(); }

}  // namespace crowdprof

// The OSMesa backend: Mesa's off-screen renderer (llvmpipe), which needs no
// display, no device and no EGL. GL/osmesa.h pulls in GL/gl.h, which clashes
// with glad's header, so this file includes nothing of render/gl.h.
//
// libOSMesa is opened at run time, not linked: it brings LLVM (over 100 MB),
// which a machine with a GPU driver, or a CPU-only run, has no use for; the
// binary then starts where OSMesa is not installed, and only this backend
// says it is missing. RTLD_LOCAL keeps its gl* symbols out of glad's way.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <array>
#include <memory>
#include <string>

#include "render/gl_context.h"
#include "render/gl_errors.h"

namespace crowdprof {

namespace {

constexpr const char* kOsMesaLibrary = "libOSMesa.so.8";

// The five entry points crowdprof calls, from the library opened once.
struct OsMesaApi {
  decltype(&OSMesaCreateContextAttribs) create_context_attribs = nullptr;
  decltype(&OSMesaDestroyContext) destroy_context = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaGetCurrentContext) get_current_context = nullptr;
  decltype(&OSMesaGetProcAddress) get_proc_address = nullptr;
  std::string problem;  // empty when every entry point was found
  SettingText fix;      // what to do instead, naming the setting
};

template <typename Function>
bool find_symbol(void* library, const char* name, Function& function) {
  function = reinterpret_cast<Function>(dlsym(library, name));
  return function != nullptr;
}

OsMesaApi open_osmesa() {
  OsMesaApi api;
  void* library = dlopen(kOsMesaLibrary, RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    api.problem = std::string("OSMesa: cannot open ") + kOsMesaLibrary + " (on Debian: apt-get install libosmesa6), ";
    api.fix = "or use {backend} egl";
    return api;
  }
  // Never closed: contexts may outlive any one caller, and the process ends soon after.
  if (!find_symbol(library, "OSMesaCreateContextAttribs", api.create_context_attribs) ||
      !find_symbol(library, "OSMesaDestroyContext", api.destroy_context) ||
      !find_symbol(library, "OSMesaMakeCurrent", api.make_current) ||
      !find_symbol(library, "OSMesaGetCurrentContext", api.get_current_context) ||
      !find_symbol(library, "OSMesaGetProcAddress", api.get_proc_address))
    api.problem = std::string("OSMesa: ") + kOsMesaLibrary + " lacks an entry point crowdprof needs";
  return api;
}

const OsMesaApi& osmesa() {
  static const OsMesaApi api = open_osmesa();
  if (!api.problem.empty()) throw GlUnavailable(api.problem, api.fix);
  return api;
}

GlContext::Proc osmesa_proc(const char* name) {
  return osmesa().get_proc_address(name);
}

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() : GlContext(GlBackend::OsMesa, "OSMesa") {
    // No depth or stencil in OSMesa's own buffer: crowdprof draws into a
    // framebuffer object that has its own.
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              4,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    context_ = osmesa().create_context_attribs(attributes, nullptr);
    if (!context_) throw GlUnavailable("OSMesa: no OpenGL 4.3 core context (is libOSMesa built with llvmpipe?)");
    try {
      initialise();
    } catch (...) {
      osmesa().destroy_context(context_);
      throw;
    }
  }
  ~OsMesaContext() override {
    const OsMesaApi& api = osmesa();
    if (api.get_current_context() == context_) api.make_current(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    api.destroy_context(context_);
  }

 protected:
  // OSMesa needs a buffer to make a context current; a pixel is enough.
  bool bind() override { return osmesa().make_current(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1) == GL_TRUE; }
  Loader loader() const override { return osmesa_proc; }

 private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> pixel_{};
};

}  // namespace

std::unique_ptr<GlContext> create_osmesa_context() {
  return std::make_unique<OsMesaContext>();
}

}  // namespace crowdprof

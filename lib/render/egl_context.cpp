// The EGL backend: a GPU through EGL_EXT_device_enumeration and
// EGL_EXT_platform_device when one answers, else Mesa's surfaceless platform
// (llvmpipe on a machine without a GPU), else Mesa's software device. No window
// system, no X: a context with no surface, rendering into framebuffer objects.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "render/gl_context.h"
#include "render/gl_errors.h"

namespace crowdprof {

namespace {

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  size_t length = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length)
    if ((p == list || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0')) return true;
  return false;
}

std::string egl_error_text() {
  EGLint error = eglGetError();
  switch (error) {
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return "EGL error " + std::to_string(error);
  }
}

GlContext::Proc egl_proc(const char* name) {
  return eglGetProcAddress(name);
}

class EglContext final : public GlContext {
 public:
  // Takes an initialised display; throws GlUnavailable (and terminates it).
  EglContext(EGLDisplay display, std::string platform) : GlContext(GlBackend::Egl, std::move(platform)) {
    display_ = display;
    try {
      create();
      initialise();
    } catch (...) {
      release();
      eglTerminate(display_);
      throw;
    }
  }
  // The display stays initialised: EGL does not count references to it, and
  // another context of this process may still use it.
  ~EglContext() override { release(); }

 protected:
  bool bind() override { return eglMakeCurrent(display_, surface_, surface_, context_) == EGL_TRUE; }
  Loader loader() const override { return egl_proc; }

 private:
  void create() {
    const char* extensions = eglQueryString(display_, EGL_EXTENSIONS);
    if (!eglBindAPI(EGL_OPENGL_API)) throw GlUnavailable(platform() + ": no desktop OpenGL (" + egl_error_text() + ")");
    bool surfaceless = has_extension(extensions, "EGL_KHR_surfaceless_context");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!surfaceless || !has_extension(extensions, "EGL_KHR_no_config_context")) {
      // A pbuffer-capable config: without EGL_PBUFFER_BIT some drivers offer
      // only window configs, which a headless display cannot use.
      const EGLint wanted[] = {EGL_SURFACE_TYPE,
                               EGL_PBUFFER_BIT,
                               EGL_RENDERABLE_TYPE,
                               EGL_OPENGL_BIT,
                               EGL_RED_SIZE,
                               8,
                               EGL_GREEN_SIZE,
                               8,
                               EGL_BLUE_SIZE,
                               8,
                               EGL_NONE};
      EGLint count = 0;
      if (!eglChooseConfig(display_, wanted, &config, 1, &count) || count < 1)
        throw GlUnavailable(platform() + ": no OpenGL pbuffer config");
    }
    const EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attributes);
    if (context_ == EGL_NO_CONTEXT)
      throw GlUnavailable(platform() + ": no OpenGL 4.3 core context (" + egl_error_text() + ")");
    if (!surfaceless) {
      const EGLint size[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
      surface_ = eglCreatePbufferSurface(display_, config, size);
      if (surface_ == EGL_NO_SURFACE) throw GlUnavailable(platform() + ": no pbuffer (" + egl_error_text() + ")");
    }
  }

  void release() {
    if (eglGetCurrentContext() == context_ && context_ != EGL_NO_CONTEXT)
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    surface_ = EGL_NO_SURFACE;
    context_ = EGL_NO_CONTEXT;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
};

// One way to a display, tried in order until one gives a context.
struct Candidate {
  EGLenum platform;
  void* native;
  std::string name;
};

}  // namespace

std::unique_ptr<GlContext> create_egl_context() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client || !has_extension(client, "EGL_EXT_platform_base"))
    throw GlUnavailable("EGL: no EGL implementation with EGL_EXT_platform_base (install libegl-mesa0)");
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_display) throw GlUnavailable("EGL: eglGetPlatformDisplayEXT missing");

  std::vector<Candidate> hardware, software;
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (has_extension(client, "EGL_EXT_platform_device") && query_devices && query_string &&
      (has_extension(client, "EGL_EXT_device_enumeration") || has_extension(client, "EGL_EXT_device_base"))) {
    EGLint count = 0;
    std::vector<EGLDeviceEXT> devices;
    if (query_devices(0, nullptr, &count) && count > 0) {
      devices.resize(static_cast<size_t>(count));
      if (!query_devices(count, devices.data(), &count)) count = 0;
      devices.resize(static_cast<size_t>(count));
    }
    for (size_t i = 0; i < devices.size(); ++i) {
      const char* extensions = query_string(devices[i], EGL_EXTENSIONS);
      std::string name = "EGL device " + std::to_string(i);
      if (has_extension(extensions, "EGL_EXT_device_drm"))
        if (const char* file = query_string(devices[i], EGL_DRM_DEVICE_FILE_EXT))
          name = "EGL device " + std::string(file);
      // Mesa lists its software renderer as a device too: the surfaceless
      // platform below reaches the same, so it only comes last.
      bool is_software = has_extension(extensions, "EGL_MESA_device_software");
      (is_software ? software : hardware).push_back({EGL_PLATFORM_DEVICE_EXT, devices[i], name});
    }
  }
  std::vector<Candidate> candidates = hardware;
  if (has_extension(client, "EGL_MESA_platform_surfaceless"))
    candidates.push_back({EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, "EGL surfaceless platform"});
  candidates.insert(candidates.end(), software.begin(), software.end());
  if (candidates.empty()) throw GlUnavailable("EGL: no GPU device and no surfaceless platform");

  std::string failures;
  for (const Candidate& c : candidates) {
    EGLDisplay display = get_display(c.platform, c.native, nullptr);
    std::string why;
    if (display == EGL_NO_DISPLAY) {
      why = "no display";
    } else if (!eglInitialize(display, nullptr, nullptr)) {
      why = "eglInitialize failed (" + egl_error_text() + ")";
    } else {
      try {
        return std::make_unique<EglContext>(display, c.name);
      } catch (const GlUnavailable& e) {
        why = e.what();
      }
    }
    if (why.rfind(c.name, 0) != 0) why = c.name + ": " + why;
    failures += (failures.empty() ? "" : "; ") + why;
  }
  throw GlUnavailable("EGL: " + failures);
}

}  // namespace crowdprof

#include "render/gl_context.h"

#include "render/gl.h"
#include "render/gl_errors.h"

namespace crowdprof {

namespace {
// The context glad's function pointers were last loaded from. Contexts are made
// current on the thread that runs the frames only.
const GlContext* g_loaded = nullptr;
constexpr int kMinMajor = 4, kMinMinor = 3;
}  // namespace

std::string_view to_string(GlBackend backend) {
  return backend == GlBackend::Egl ? "egl" : "osmesa";
}

GlContext::~GlContext() {
  if (g_loaded == this) g_loaded = nullptr;
}

void GlContext::make_current() {
  if (!bind()) throw GlUnavailable(platform_ + ": cannot make the GL context current");
  if (g_loaded == this) return;
  g_loaded = nullptr;
  // glad's loader type is this same function type, spelled with its own names.
  if (gladLoadGL(reinterpret_cast<GLADloadfunc>(loader())) == 0)
    throw GlUnavailable(platform_ + ": cannot load the OpenGL functions");
  g_loaded = this;
}

void GlContext::initialise() {
  make_current();
  auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  renderer_ = text(GL_RENDERER);
  version_ = text(GL_VERSION);
  vendor_ = text(GL_VENDOR);
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  if (major < kMinMajor || (major == kMinMajor && minor < kMinMinor) || !(profile & GL_CONTEXT_CORE_PROFILE_BIT))
    throw GlUnavailable(platform_ + " (" + renderer_ + ") offers OpenGL " + version_ +
                        "; crowdprof needs a 4.3 core profile");
  glGetError();  // a fresh context may hold an error from the loader's probing
}

std::unique_ptr<GlContext> create_context(GlBackend backend) {
  return backend == GlBackend::Egl ? create_egl_context() : create_osmesa_context();
}

std::unique_ptr<GlContext> open_backend(BackendChoice choice, SettingText* warning, const BackendOpeners& openers) {
  switch (choice) {
    case BackendChoice::None:
      return nullptr;
    case BackendChoice::Egl:
      return openers.egl();
    case BackendChoice::OsMesa:
      return openers.osmesa();
    case BackendChoice::Auto:
      break;
  }
  std::string egl_failure;
  try {
    return openers.egl();
  } catch (const GlUnavailable& e) {
    egl_failure = e.marked();
  }
  try {
    return openers.osmesa();
  } catch (const GlUnavailable& e) {
    if (warning) *warning = "no usable GL (" + egl_failure + "; " + e.marked() + "): running with {backend} none";
  }
  return nullptr;
}

}  // namespace crowdprof

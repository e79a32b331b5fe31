// A headless OpenGL 4.3+ core context from one of two backends: EGL (a GPU
// through EGL_EXT_device_enumeration when the machine has one, else Mesa's
// surfaceless platform) or OSMesa (Mesa's software renderer, no display at all).
// Rendering goes to a framebuffer object (framebuffer.h), never to a window.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "base/backend_choice.h"
#include "base/errors.h"

namespace crowdprof {

enum class GlBackend : uint8_t { Egl, OsMesa };

std::string_view to_string(GlBackend backend);  // "egl", "osmesa"

class GlContext {
 public:
  // A GL function by name, as eglGetProcAddress or OSMesaGetProcAddress give it.
  using Proc = void (*)();
  using Loader = Proc (*)(const char* name);

  virtual ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes the context current on this thread and points glad's functions at
  // it. EGL's and OSMesa's function pointers differ, so glad is reloaded
  // whenever another context was current. Throws GlUnavailable.
  void make_current();

  GlBackend backend() const { return backend_; }
  // How the backend got its device: "EGL device /dev/dri/renderD128",
  // "EGL surfaceless platform", "OSMesa".
  const std::string& platform() const { return platform_; }
  // GL_RENDERER, GL_VERSION and GL_VENDOR, read when the context was made.
  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }
  const std::string& vendor() const { return vendor_; }

 protected:
  GlContext(GlBackend backend, std::string platform) : backend_(backend), platform_(std::move(platform)) {}
  // Makes the native context current; false when the backend refuses.
  virtual bool bind() = 0;
  virtual Loader loader() const = 0;
  // For a backend's create function: make current, load GL, check the version
  // (4.3 core at least), read the renderer's name. Throws GlUnavailable.
  void initialise();

 private:
  GlBackend backend_;
  std::string platform_, renderer_, version_, vendor_;
};

// Each throws GlUnavailable saying what was tried and why it failed.
std::unique_ptr<GlContext> create_egl_context();
std::unique_ptr<GlContext> create_osmesa_context();
std::unique_ptr<GlContext> create_context(GlBackend backend);

// How each backend's context is made: the real ones, or stand-ins in tests.
struct BackendOpeners {
  std::function<std::unique_ptr<GlContext>()> egl = create_egl_context;
  std::function<std::unique_ptr<GlContext>()> osmesa = create_osmesa_context;
};

// The context `choice` asks for, current. None gives null. Auto tries EGL, then
// OSMesa, and when neither works gives null and says why in *warning (one
// line); an explicit backend that fails throws GlUnavailable.
std::unique_ptr<GlContext> open_backend(BackendChoice choice, SettingText* warning, const BackendOpeners& openers = {});

}  // namespace crowdprof

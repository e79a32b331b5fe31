// The GL layer on its own: contexts from each backend, shader errors that name
// the file and the line, GL errors that name the stage, framebuffer limits.
// GL tests skip when no backend can make a context on this machine.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "base/errors.h"
#include "render/crowd_renderer.h"
#include "render/framebuffer.h"
#include "render/gl.h"
#include "render/gl_context.h"
#include "render/gl_errors.h"
#include "render/gl_program.h"
#include "render/shader_sources.h"
#include "render_support.h"

using namespace crowdprof;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST(RenderGl, BackendNames) {
  EXPECT_EQ(parse_backend("auto"), BackendChoice::Auto);
  EXPECT_EQ(parse_backend("egl"), BackendChoice::Egl);
  EXPECT_EQ(parse_backend("osmesa"), BackendChoice::OsMesa);
  EXPECT_EQ(parse_backend("none"), BackendChoice::None);
  EXPECT_FALSE(parse_backend("vulkan"));
  EXPECT_FALSE(parse_backend("EGL"));
  EXPECT_EQ(to_string(GlBackend::Egl), "egl");
  EXPECT_EQ(to_string(GlBackend::OsMesa), "osmesa");
}

TEST(RenderGl, BoneLimitFollowsTheThesis) {
  // Half the vertex uniform components, in 16-float matrices, capped at 128.
  EXPECT_EQ(gpu_joint_limit(4096, 128), 128u);
  EXPECT_EQ(gpu_joint_limit(16384, 128), 128u);
  EXPECT_EQ(gpu_joint_limit(1024, 128), 32u);
  EXPECT_EQ(gpu_joint_limit(4096, 8), 8u);
  EXPECT_EQ(gpu_joint_limit(0, 128), 0u);
  EXPECT_EQ(gpu_joint_limit(-1, 128), 0u);
}

TEST(RenderGl, DefinesKeepTheFilesLineNumbers) {
  std::string source = "// comment\n#version 430 core\nvoid main() {}\n";
  std::string out = with_defines(source, "#define MAX_BONES 12\n");
  EXPECT_EQ(out, "// comment\n#version 430 core\n#define MAX_BONES 12\n#line 3\nvoid main() {}\n");
  EXPECT_EQ(first_log_line("0:12(5): error: syntax error\n"), 12);     // Mesa
  EXPECT_EQ(first_log_line("0(7) : error C0000: syntax error\n"), 7);  // NVIDIA
  EXPECT_EQ(first_log_line("warning: something\n0:4(1): error: x\n"), 4);
  EXPECT_EQ(first_log_line("error: no line at all\n"), 0);
  EXPECT_EQ(first_log_line(""), 0);
}

TEST(RenderGl, EveryShaderIsEmbedded) {
  for (const char* name : {"shaders/crowd.vert", "shaders/hwskin.vert", "shaders/lit.frag"})
    EXPECT_TRUE(contains(std::string(embedded_shader(name)), "#version 430 core")) << name;
  EXPECT_THROW(embedded_shader("shaders/none.vert"), std::logic_error);
}

TEST(RenderGl, EachBackendGivesA43CoreContext) {
  int opened = 0;
  for (GlBackend backend : {GlBackend::Egl, GlBackend::OsMesa}) {
    std::string why;
    auto context = test::try_context(backend, &why);
    if (!context) {
      std::cout << "[ info ] " << to_string(backend) << " unavailable: " << why << "\n";
      continue;
    }
    ++opened;
    EXPECT_EQ(context->backend(), backend);
    EXPECT_FALSE(context->renderer().empty());
    EXPECT_FALSE(context->platform().empty());
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    EXPECT_GE(major * 10 + minor, 43) << context->version();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  }
  if (opened == 0) GTEST_SKIP() << "no GL backend on this machine";
}

TEST(RenderGl, AShaderThatDoesNotCompileNamesItsFileLineAndLog) {
  OPEN_GL_OR_SKIP(context);
  std::string broken =
      "#version 430 core\nout vec4 colour;\nvoid main() {\n  colour = vec4(1.0) * undefined_thing;\n}\n";
  std::vector<ShaderStage> stages = {
      {GL_FRAGMENT_SHADER, "shaders/broken.frag", with_defines(broken, "#define X 1\n")}};
  try {
    build_program(stages);
    FAIL() << "a broken shader compiled";
  } catch (const GlError& e) {
    std::string message = e.what();
    EXPECT_TRUE(contains(message, "shaders/broken.frag:4: does not compile")) << message;
    EXPECT_TRUE(contains(message, "undefined_thing")) << message;  // the driver's log
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(RenderGl, TheShippedShadersBuild) {
  OPEN_GL_OR_SKIP(context);
  auto stage = [](GLenum type, const char* name, const std::string& defines) {
    return ShaderStage{type, name, with_defines(embedded_shader(name), defines)};
  };
  for (const char* vertex : {"shaders/crowd.vert", "shaders/hwskin.vert"}) {
    std::vector<ShaderStage> stages = {stage(GL_VERTEX_SHADER, vertex, "#define MAX_BONES 128\n"),
                                       stage(GL_FRAGMENT_SHADER, "shaders/lit.frag", "")};
    GlProgram program(stages);
    EXPECT_NE(program.id(), 0u) << vertex;
    EXPECT_GE(program.uniform("model"), 0);
    EXPECT_THROW(program.uniform("no_such_uniform"), GlError);
  }
}

TEST(RenderGl, AGlErrorNamesItselfAndTheStage) {
  OPEN_GL_OR_SKIP(context);
  check_gl("nothing");  // no error pending: nothing happens
  // Core profile: binding a name that was never generated is GL_INVALID_OPERATION.
  glBindBuffer(GL_ARRAY_BUFFER, 987654);
  try {
    check_gl("Rasterizer");
    FAIL() << "no error reported";
  } catch (const GlError& e) {
    EXPECT_STREQ(e.what(), "GL error GL_INVALID_OPERATION during Rasterizer");
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));  // drained
  EXPECT_EQ(gl_error_name(0x1234), "0x1234");
}

TEST(RenderGl, FramebufferSizeLimits) {
  OPEN_GL_OR_SKIP(context);
  int limit = max_framebuffer_size();
  EXPECT_GE(limit, 1024);
  EXPECT_THROW(Framebuffer(0, 90), UsageError);
  EXPECT_THROW(Framebuffer(160, 0), UsageError);
  try {
    Framebuffer too_big(limit + 1, 90);
    FAIL() << "a framebuffer past GL_MAX_RENDERBUFFER_SIZE";
  } catch (const SettingsUsageError& e) {
    EXPECT_TRUE(contains(e.what(), "resolution")) << e.what();  // the setting: cli/ spells --resolution
    EXPECT_TRUE(contains(e.what(), std::to_string(limit))) << e.what();
  }
  Framebuffer small(17, 5);
  small.bind();
  glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  std::vector<uint8_t> pixels = small.read_rgba();
  ASSERT_EQ(pixels.size(), 17u * 5u * 4u);
  EXPECT_EQ(pixels[0], 255);
  EXPECT_EQ(pixels[1], 0);
  EXPECT_EQ(pixels[3], 255);
}

TEST(RenderGl, AutoFallsBackToNoneSayingWhy) {
  BackendOpeners broken;
  broken.egl = []() -> std::unique_ptr<GlContext> { throw GlUnavailable("EGL: no display here"); };
  broken.osmesa = []() -> std::unique_ptr<GlContext> { throw GlUnavailable("OSMesa: no context here"); };
  SettingText marked;
  EXPECT_EQ(open_backend(BackendChoice::Auto, &marked, broken), nullptr);
  std::string warning = marked.str();  // the library's terms: the setting, not the option
  EXPECT_TRUE(contains(warning, "EGL: no display here")) << warning;
  EXPECT_TRUE(contains(warning, "OSMesa: no context here")) << warning;
  EXPECT_TRUE(contains(warning, "backend none")) << warning;
  EXPECT_FALSE(contains(warning, "--backend")) << warning;
  EXPECT_EQ(warning.find('\n'), std::string::npos) << warning;  // one line
  // Asked for by name, a backend that fails is an error, not a fallback.
  EXPECT_THROW(open_backend(BackendChoice::Egl, &marked, broken), GlUnavailable);
  EXPECT_THROW(open_backend(BackendChoice::OsMesa, &marked, broken), GlUnavailable);
  marked = {};
  EXPECT_EQ(open_backend(BackendChoice::None, &marked, broken), nullptr);
  EXPECT_TRUE(marked.empty());
}

// The headless EGL context: 4.5 core, software detection, NIMBUS_EGL_DEVICE, coexisting
// contexts, and a clear GlUnavailable (no crash) when no EGL vendor library can be loaded.
#include <gtest/gtest.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <optional>

#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "support/run_nimbus.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

// Sets an environment variable for one scope, restoring the old value after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

std::string self_executable() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
}

TEST(GlContext, IsOpenGl45Core) {
  NIMBUS_REQUIRE_GL();
  const GlContext& ctx = *test::shared_gl().context;
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 45) << ctx.version();
  EXPECT_NE(profile & GL_CONTEXT_CORE_PROFILE_BIT, 0);
  EXPECT_EQ(profile & GL_CONTEXT_COMPATIBILITY_PROFILE_BIT, 0);
  EXPECT_NE(ctx.version().find("Core Profile"), std::string::npos) << ctx.version();
  EXPECT_FALSE(ctx.renderer().empty());
  EXPECT_FALSE(ctx.platform().empty());
  // llvmpipe is Mesa's software renderer.
  if (ctx.renderer().find("llvmpipe") != std::string::npos) {
    EXPECT_TRUE(ctx.is_software());
  }
  check_gl("context queries");
  std::printf("GL: %s | %s | %s\n", ctx.renderer().c_str(), ctx.version().c_str(), ctx.platform().c_str());
}

TEST(GlContext, TwoContextsCoexistAndOutliveEachOther) {
  NIMBUS_REQUIRE_GL();
  GLuint shared_texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &shared_texture);
  ASSERT_NE(shared_texture, 0u);
  {
    auto second = GlContext::create_headless();  // made current
    ASSERT_EQ(second->renderer().empty(), false);
    // Objects are per context (no sharing): the first context's texture is unknown here.
    EXPECT_EQ(glIsTexture(shared_texture), GL_FALSE);
  }  // destroyed: must not terminate the display under the first context
  test::shared_gl().context->make_current();
  EXPECT_EQ(glIsTexture(shared_texture), GL_TRUE);
  glDeleteTextures(1, &shared_texture);
  check_gl("after a second context came and went");
}

TEST(GlContext, SoftwareCanBeForced) {
  NIMBUS_REQUIRE_GL();
  ScopedEnv env("NIMBUS_EGL_DEVICE", "software");
  std::unique_ptr<GlContext> ctx;
  try {
    ctx = GlContext::create_headless();
  } catch (const GlUnavailable& e) {
    // A GPU-only machine may have no software EGL; the message must say it was forced.
    EXPECT_NE(std::string(e.what()).find("NIMBUS_EGL_DEVICE=software"), std::string::npos) << e.what();
    return;
  }
  EXPECT_TRUE(ctx->is_software()) << ctx->renderer();
}

TEST(GlContext, BadDeviceChoiceIsNamed) {
  {
    ScopedEnv env("NIMBUS_EGL_DEVICE", "gpu0");
    try {
      GlContext::create_headless();
      FAIL() << "NIMBUS_EGL_DEVICE=gpu0 accepted";
    } catch (const GlUnavailable& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("no OpenGL 4.5 core context available: ", 0), 0u) << what;
      EXPECT_NE(what.find("NIMBUS_EGL_DEVICE='gpu0'"), std::string::npos) << what;
    }
  }
  if (test::shared_gl().context) {  // the device list exists only where EGL does
    ScopedEnv env("NIMBUS_EGL_DEVICE", "4096");
    try {
      GlContext::create_headless();
      FAIL() << "NIMBUS_EGL_DEVICE=4096 accepted";
    } catch (const GlUnavailable& e) {
      EXPECT_NE(std::string(e.what()).find("NIMBUS_EGL_DEVICE=4096 is out of range"), std::string::npos)
          << e.what();
    }
  }
}

// Run only in a child process (see the next test): glvnd reads __EGL_VENDOR_LIBRARY_FILENAMES once,
// when EGL is first used, so the parent, which already has a context, cannot test it itself.
TEST(GlContextChild, DISABLED_ReportCreateHeadless) {
  try {
    auto ctx = GlContext::create_headless();
    std::printf("child-result: created %s\n", ctx->renderer().c_str());
  } catch (const GlUnavailable& e) {
    std::printf("child-result: unavailable: %s\n", e.what());
  }
}

TEST(GlContext, MissingEglVendorGivesAClearError) {
  const std::string self = self_executable();
  ASSERT_FALSE(self.empty());
  const test::RunResult r = test::run_command(
      "env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json NIMBUS_EGL_DEVICE= '" + self +
      "' --gtest_also_run_disabled_tests --gtest_filter=GlContextChild.DISABLED_ReportCreateHeadless");
  EXPECT_EQ(r.code, 0) << r.output;  // no crash, no abort
  const auto at = r.output.find("child-result: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
  EXPECT_EQ(line.rfind("child-result: unavailable: no OpenGL 4.5 core context available: ", 0), 0u) << line;
  EXPECT_NE(line.find("no EGL vendor library"), std::string::npos) << line;
}

}  // namespace
}  // namespace nimbus::render

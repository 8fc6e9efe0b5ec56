// `nimbus bench gl` (samples/bench/gl_limits.hpp): a tiny run prints a row per size whose every
// rate is a positive number (the slice round trip among them), and the GPU timer counts the
// fragments a full-screen pass shades (one per pixel, give or take the driver's blocks at the
// frame's edge) where the driver counts them; bad options are usage errors.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "nimbus/render/gl/gpu_timer.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "support/run_nimbus.hpp"
#include "test_gl_support.hpp"

namespace {

TEST(BenchGl, TinyRunPrintsPositiveRatesPerSize) {
  NIMBUS_REQUIRE_GL();
  const auto r = nimbus::test::run_nimbus("bench gl --sizes 64x36,32x18 --repeats 1");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* size : {"| 64x36 |", "| 32x18 |"}) {
    const std::size_t at = r.output.find(size);
    ASSERT_NE(at, std::string::npos) << r.output;
    std::istringstream row(r.output.substr(at + std::string(size).size()));
    for (int i = 0; i < 5; ++i) {  // four rates in M/s, then slice round trips per second
      double rate = -1.0;
      char bar = 0;
      row >> rate >> bar;
      EXPECT_GT(rate, 0.0) << size << " column " << i << "\n" << r.output;
      EXPECT_EQ(bar, '|');
    }
  }
}

TEST(BenchGl, BadOptionsAreUsageErrors) {
  for (const char* args : {"bench gl --sizes 0x10", "bench gl --repeats 0", "bench gl --repeats 101", "bench gl --sizes ''"}) {
    const auto r = nimbus::test::run_nimbus(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
  }
}

// A full-screen pass of w x h shades w x h fragments (llvmpipe counts 48 x 24 for 48 x 20:
// whole blocks): the count bench view reads each pass's time against.
TEST(GpuTimer, CountsTheFragmentsAFullScreenPassShades) {
  NIMBUS_REQUIRE_GL();
  using namespace nimbus::render;
  const int w = 48, h = 20;
  const GlTexture target = make_texture_2d(GL_RGBA32F, w, h);
  const GlFramebuffer fb = make_framebuffer({{GL_COLOR_ATTACHMENT0, target.id()}});
  const ShaderProgram fill = ShaderProgram::from_sources(
      {{"test_fill.frag.glsl", "#version 450 core\nin vec2 uv;\nout vec4 c;\nvoid main() { c = vec4(uv, 0.0, 1.0); }\n"}},
      {"fullscreen.vert.glsl", "test_fill.frag.glsl"});
  const GlVertexArray vao = make_vertex_array();
  glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
  glViewport(0, 0, w, h);
  GpuTimer timer(2);
  fill.use();
  timer.time(1, [&] {
    draw_fullscreen_triangle(vao);
    draw_fullscreen_triangle(vao);
  });
  timer.finish();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (timer.fragments(1) < 0.0) GTEST_SKIP() << "the driver does not count fragment shader invocations";
  // llvmpipe counts whole blocks at the frame's edge: up to 8 rows and columns more.
  const auto up8 = [](int n) { return 8.0 * ((n + 7) / 8); };
  EXPECT_GE(timer.fragments(1), 2.0 * w * h);
  EXPECT_LE(timer.fragments(1), 2.0 * up8(w) * up8(h));
  EXPECT_EQ(timer.fragments(0), 0.0);
  EXPECT_EQ(GpuTimer(1, false).fragments(0), -1.0);  // a disabled timer counts nothing
}

}  // namespace

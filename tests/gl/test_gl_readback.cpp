// A full-screen pass writes known values that read back exactly, row 0 at the top; every uniform
// setter reaches the shader; resources report errors by name; GPU timing gives a duration.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "nimbus/render/gl/gpu_timer.hpp"
#include "nimbus/render/gl/readback.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

constexpr int kW = 7, kH = 5;  // odd and unequal, so a transposed or flipped read is caught

TEST(GlReadback, FullScreenPassReadsBackExactlyTopRowFirst) {
  NIMBUS_REQUIRE_GL();
  GlTexture coords = make_texture_2d(GL_RGBA32F, kW, kH, {GL_NEAREST, GL_NEAREST});
  GlTexture uv = make_texture_2d(GL_RGBA32F, kW, kH, {GL_NEAREST, GL_NEAREST});
  GlFramebuffer fb = make_framebuffer({{GL_COLOR_ATTACHMENT0, coords.id()}, {GL_COLOR_ATTACHMENT1, uv.id()}});
  ShaderProgram program =
      ShaderProgram::from_sources(test::test_shader_files(), {"fullscreen.vert.glsl", "test_pattern.frag.glsl"});
  program.set("value", 0.375f);
  GlVertexArray vao = make_vertex_array();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb.id());
  glViewport(0, 0, kW, kH);
  program.use();
  draw_fullscreen_triangle(vao);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  check_gl("full-screen pass");

  const Image from_fb = read_rgba(fb, kW, kH);
  const Image from_tex = read_rgba(coords, kW, kH);
  const Image uvs = read_rgba(fb, kW, kH, GL_COLOR_ATTACHMENT1);
  ASSERT_EQ(from_fb.width, kW);
  ASSERT_EQ(from_fb.height, kH);
  for (int row = 0; row < kH; ++row) {
    for (int x = 0; x < kW; ++x) {
      const float* p = from_fb.pixel(x, row);
      // Window coordinates are pixel centres, exact in float; row 0 is the top (largest GL y).
      EXPECT_EQ(p[0], x + 0.5f) << x << "," << row;
      EXPECT_EQ(p[1], (kH - 1 - row) + 0.5f) << x << "," << row;
      EXPECT_EQ(p[2], 0.375f);  // through test_lib_scale (x 1.0)
      EXPECT_EQ(p[3], 1.0f);
      for (int c = 0; c < 4; ++c) EXPECT_EQ(from_tex.pixel(x, row)[c], p[c]);
      // uv interpolated over the triangle: (x + 0.5) / w, bottom-up; 1e-6 for interpolation.
      const float* q = uvs.pixel(x, row);
      EXPECT_NEAR(q[0], (x + 0.5) / kW, 1e-6);
      EXPECT_NEAR(q[1], ((kH - 1 - row) + 0.5) / kH, 1e-6);
    }
  }
  const std::vector<float> red = read_red(fb, kW, kH);
  const std::vector<float> red_tex = read_red(coords, kW, kH);
  ASSERT_EQ(red.size(), static_cast<std::size_t>(kW * kH));
  for (int i = 0; i < kW * kH; ++i) {
    EXPECT_EQ(red[i], from_fb.rgba[i * 4]);
    EXPECT_EQ(red_tex[i], from_fb.rgba[i * 4]);
  }
}

TEST(GlReadback, EveryUniformSetterReachesTheShader) {
  NIMBUS_REQUIRE_GL();
  GlTexture t0 = make_texture_2d(GL_RGBA32F, 2, 2), t1 = make_texture_2d(GL_RGBA32F, 2, 2),
            t2 = make_texture_2d(GL_RGBA32F, 2, 2), t3 = make_texture_2d(GL_RGBA32F, 2, 2);
  GlFramebuffer fb = make_framebuffer({{GL_COLOR_ATTACHMENT0, t0.id()},
                                       {GL_COLOR_ATTACHMENT1, t1.id()},
                                       {GL_COLOR_ATTACHMENT2, t2.id()},
                                       {GL_COLOR_ATTACHMENT3, t3.id()}});
  ShaderProgram program =
      ShaderProgram::from_sources(test::test_shader_files(), {"fullscreen.vert.glsl", "test_uniforms.frag.glsl"});
  const glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)) * glm::scale(glm::mat4(1.0f), glm::vec3(2));
  program.set("i1", -7);
  program.set("f1", 0.25f);
  program.set("f2", glm::vec2(4.0f, 0.5f));
  program.set("f3", glm::vec3(1.0f, -2.0f, 3.0f));
  program.set("f4", glm::vec4(9, 8, 7, 6));
  program.set("i2", glm::ivec2(11, -12));
  program.set("m4", m);
  program.set("u1", 42u);
  // A name no stage declares is an error (a misspelt uniform is never silently ignored); one the
  // compiler dropped because this shader never reads it is skipped.
  EXPECT_THROW(program.set("not_a_uniform", 1.0f), UniformError);
  EXPECT_THROW(program.set("f_1", 1.0f), UniformError);
  EXPECT_NO_THROW(program.set("unused_f", 1.0f));
  EXPECT_FALSE(program.has_uniform("unused_f"));
  EXPECT_TRUE(program.declares("unused_f"));
  EXPECT_FALSE(program.declares("not_a_uniform"));
  EXPECT_FALSE(program.has_uniform("not_a_uniform"));
  EXPECT_TRUE(program.has_uniform("m4"));
  GlVertexArray vao = make_vertex_array();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb.id());
  glViewport(0, 0, 2, 2);
  program.use();
  draw_fullscreen_triangle(vao);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  check_gl("uniform pass");
  const Image out0 = read_rgba(fb, 2, 2, GL_COLOR_ATTACHMENT0);
  const float* a = out0.pixel(1, 0);
  EXPECT_EQ(a[0], -7.0f);
  EXPECT_EQ(a[1], 0.25f);
  EXPECT_EQ(a[2], 11.0f);
  EXPECT_EQ(a[3], -12.0f);
  const Image b = read_rgba(fb, 2, 2, GL_COLOR_ATTACHMENT1);
  EXPECT_EQ(b.pixel(0, 1)[0], 9.0f);
  EXPECT_EQ(b.pixel(0, 1)[3], 6.0f);
  // m4 * (f3, f2.x) + (0, 0, 0, f2.y), in double: m = T(1,2,3) S(2), w = 4.
  const Image c = read_rgba(fb, 2, 2, GL_COLOR_ATTACHMENT2);
  const double expect[4] = {2 * 1.0 + 1 * 4, 2 * -2.0 + 2 * 4, 2 * 3.0 + 3 * 4, 4 + 0.5};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(c.pixel(1, 1)[i], expect[i], 1e-6) << i;
  EXPECT_EQ(read_rgba(fb, 2, 2, GL_COLOR_ATTACHMENT3).pixel(0, 0)[0], 42.0f);
}

TEST(GlReadback, DepthAndCubeTargetsAttach) {
  NIMBUS_REQUIRE_GL();
  GlTexture depth = make_depth_texture(4, 3);
  GlFramebuffer fb = make_framebuffer({{GL_DEPTH_ATTACHMENT, depth.id()}});
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb.id());
  glViewport(0, 0, 4, 3);
  glClearDepthf(0.625f);  // exact in 32-bit float depth
  glClear(GL_DEPTH_BUFFER_BIT);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  for (float d : read_depth_texture(depth.id(), 4, 3)) EXPECT_EQ(d, 0.625f);

  GlTexture cube = make_depth_cube_texture(8, {GL_DEPTH_COMPONENT32F, true, GL_LINEAR});
  for (int face = 0; face < 6; ++face) {
    GlFramebuffer f = make_framebuffer({{GL_DEPTH_ATTACHMENT, cube.id(), 0, face}});
    EXPECT_NE(f.id(), 0u);
  }
  GlFramebuffer layered = make_framebuffer({{GL_DEPTH_ATTACHMENT, cube.id()}});
  EXPECT_NE(layered.id(), 0u);
  check_gl("depth targets");
}

TEST(GlReadback, ErrorsAreNamed) {
  NIMBUS_REQUIRE_GL();
  // A depth texture as a color attachment is an incomplete attachment.
  GlTexture depth = make_depth_texture(4, 4);
  try {
    make_framebuffer({{GL_COLOR_ATTACHMENT0, depth.id()}});
    FAIL() << "incomplete framebuffer accepted";
  } catch (const GlError& e) {
    EXPECT_EQ(std::string(e.what()), "framebuffer incomplete: GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT");
  }
  glGetError();  // whatever the failed attach left behind
  glBindTexture(GL_TEXTURE_2D, 0xFFFFFFu);  // not a name from glGen*/glCreate*: GL_INVALID_OPERATION
  try {
    check_gl("binding a bogus texture");
    FAIL() << "check_gl saw no error";
  } catch (const GlError& e) {
    EXPECT_EQ(std::string(e.what()), "GL error GL_INVALID_OPERATION at binding a bogus texture");
  }
  EXPECT_NO_THROW(check_gl("clean"));
  EXPECT_THROW(make_texture_2d(GL_RGBA32F, 0, 4), std::invalid_argument);
  EXPECT_THROW(make_texture_2d(GL_RGBA32F, 4, 4, {GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, 4}), std::invalid_argument);
  EXPECT_THROW(read_rgba(0u, 0, 1), std::invalid_argument);
  GlTexture small = make_texture_2d(GL_RGBA32F, 4, 4);
  EXPECT_THROW(read_rgba(small, 5, 4), std::invalid_argument);
}

TEST(GlReadback, MoveOnlyOwnersTransferTheName) {
  NIMBUS_REQUIRE_GL();
  GlTexture a = make_texture_2d(GL_R32F, 2, 2);
  const GLuint id = a.id();
  GlTexture b = std::move(a);
  EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is specified
  EXPECT_EQ(b.id(), id);
  EXPECT_EQ(glIsTexture(id), GL_TRUE);
  b = GlTexture();
  EXPECT_EQ(glIsTexture(id), GL_FALSE);
}

TEST(GlReadback, GpuTimeMeasuresTheDraw) {
  NIMBUS_REQUIRE_GL();
  GlTexture t = make_texture_2d(GL_RGBA32F, 64, 64);
  GlFramebuffer fb = make_framebuffer({{GL_COLOR_ATTACHMENT0, t.id()}});
  ShaderProgram program =
      ShaderProgram::from_sources(test::test_shader_files(), {"fullscreen.vert.glsl", "test_uniforms.frag.glsl"});
  GlVertexArray vao = make_vertex_array();
  int calls = 0;
  const GpuTiming timing = gpu_time([&] {
    ++calls;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb.id());
    glViewport(0, 0, 64, 64);
    program.use();
    draw_fullscreen_triangle(vao);
  });
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  EXPECT_EQ(calls, 1);
  EXPECT_TRUE(std::isfinite(timing.ms));
  EXPECT_GE(timing.ms, 0.0);
  EXPECT_TRUE(timing.method == "GL_TIME_ELAPSED query" || timing.method == "glFinish + steady_clock") << timing.method;
  std::printf("64x64 full-screen pass: %.3f ms (%s)\n", timing.ms, timing.method.c_str());
}

}  // namespace
}  // namespace nimbus::render

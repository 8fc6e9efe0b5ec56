// The viewer's display pass (shaders/view_display.frag.glsl, lib/tonemap.glsl) against the PNG
// screenshots' encoding (render::preview_pixel): what the screen shows is what F12 saves.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

// Measured (llvmpipe): every code equal or one apart (float rounding at code boundaries).
TEST(ViewDisplay, ShaderEncodesAsThePngPreviewWithinOneCode) {
  NIMBUS_REQUIRE_GL();
  const int w = 64, h = 16;
  std::vector<float> ramp(static_cast<std::size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = ramp.data() + (static_cast<std::size_t>(y) * w + x) * 4;
      const double v = std::pow(10.0, -4.0 + 6.0 * (x + w * y) / (w * h - 1.0));  // 1e-4 .. 100
      p[0] = static_cast<float>(v);
      p[1] = static_cast<float>(0.7 * v);
      p[2] = static_cast<float>(0.4 * v + 0.01);
      p[3] = 1.0f;
    }
  GlTexture frame = make_texture_2d(GL_RGBA32F, w, h, TextureParams{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1});
  glTextureSubImage2D(frame.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, ramp.data());
  GlTexture target = make_texture_2d(GL_RGBA8, w, h, TextureParams{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1});
  GlFramebuffer fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, target.id()}});
  ShaderProgram p({"fullscreen.vert.glsl", "view_display.frag.glsl"});
  for (double stops : {0.0, 1.5}) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, w, h);
    glBindTextureUnit(contract::UNIT_SCENE_COLOR, frame.id());
    p.set("u_exposure", static_cast<float>(std::exp2(stops)));
    p.set("u_dither", 0.0f);
    p.use();
    GlVertexArray vao = make_vertex_array();
    draw_fullscreen_triangle(vao);
    std::vector<unsigned char> out(static_cast<std::size_t>(w) * h * 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    PreviewOptions po;
    po.exposure_stops = stops;
    int worst = 0, distinct = 0, last = -1;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        // The shader reads row 0 of the image at the top: GL row y shows image row h - 1 - y.
        const float* src = ramp.data() + (static_cast<std::size_t>(h - 1 - y) * w + x) * 4;
        const std::array<std::uint8_t, 3> want = preview_pixel(src, po);
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, std::abs(int(out[(static_cast<std::size_t>(y) * w + x) * 4 + c]) - int(want[c])));
        distinct += want[1] != last;
        last = want[1];
      }
    EXPECT_LE(worst, 1) << "exposure " << stops;
    EXPECT_GT(distinct, 100) << "the ramp spans the codes";
  }
}

}  // namespace
}  // namespace nimbus::render

// The viewer's display pass: a finished frame (any size) drawn over the current framebuffer's
// viewport, exposed, tone mapped and sRGB-encoded as the PNG screenshots are
// (shaders/view_display.frag.glsl).
#pragma once
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"

namespace nimbus::viewer {

class Display {
 public:
  Display();  // compiles; needs a current GL 4.5 context
  // Uploads `image` and draws it over the viewport (width x height pixels at the origin) of the
  // bound draw framebuffer. dither: one 8-bit code of triangular noise (off for exact tests).
  void draw(const render::Image& image, int width, int height, double exposure_stops, bool dither = true);

 private:
  render::ShaderProgram program_;
  render::GlVertexArray vao_;
  render::GlTexture texture_;
  int tex_w_ = 0, tex_h_ = 0;
};

}  // namespace nimbus::viewer

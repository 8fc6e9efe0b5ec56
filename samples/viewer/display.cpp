// The viewer's display pass (display.hpp).
#include "display.hpp"

#include <cmath>

#include "nimbus/render/core/shader_contract.hpp"

namespace nimbus::viewer {

Display::Display()
    : program_({"fullscreen.vert.glsl", "view_display.frag.glsl"}), vao_(render::make_vertex_array()) {}

void Display::draw(const render::Image& image, int width, int height, double exposure_stops, bool dither) {
  if (image.width != tex_w_ || image.height != tex_h_) {
    texture_ = render::make_texture_2d(GL_RGBA32F, image.width, image.height,
                                       render::TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, 1});
    tex_w_ = image.width;
    tex_h_ = image.height;
  }
  glTextureSubImage2D(texture_.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, image.rgba.data());
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glBindTextureUnit(render::contract::UNIT_SCENE_COLOR, texture_.id());
  program_.set("u_exposure", static_cast<float>(std::exp2(exposure_stops)));
  program_.set("u_dither", dither ? 1.0f : 0.0f);
  program_.use();
  render::draw_fullscreen_triangle(vao_);
  render::check_gl("viewer display");
}

}  // namespace nimbus::viewer

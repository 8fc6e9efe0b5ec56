// Pixel readback (framebuffers and textures, flipped to row 0 at the top).
#include "nimbus/render/gl/readback.hpp"

#include <algorithm>
#include <stdexcept>

namespace nimbus::render {
namespace {

void require_size(int width, int height) {
  if (width < 1) throw std::invalid_argument("width must be >= 1 (got " + std::to_string(width) + ")");
  if (height < 1) throw std::invalid_argument("height must be >= 1 (got " + std::to_string(height) + ")");
}

// GL rows run bottom-up; reverse them in place so row 0 is the top.
void flip_rows(std::vector<float>& data, int width, int height, int channels) {
  const std::size_t row = static_cast<std::size_t>(width) * channels;
  for (int y = 0; y < height / 2; ++y) {
    std::swap_ranges(data.begin() + static_cast<std::ptrdiff_t>(y * row),
                     data.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     data.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
  }
}

std::vector<float> read_framebuffer(GLuint framebuffer, int width, int height, GLenum read_buffer, GLenum format,
                                    int channels) {
  require_size(width, height);
  std::vector<float> data(static_cast<std::size_t>(width) * height * channels);
  GLint previous = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glNamedFramebufferReadBuffer(framebuffer, read_buffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadnPixels(0, 0, width, height, format, GL_FLOAT, static_cast<GLsizei>(data.size() * sizeof(float)),
                data.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
  check_gl("read_framebuffer");
  flip_rows(data, width, height, channels);
  return data;
}

std::vector<float> read_texture(GLuint texture, int width, int height, int level, GLenum format, int channels) {
  require_size(width, height);
  GLint w = 0, h = 0;
  glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_HEIGHT, &h);
  check_gl("read_texture (size query)");
  if (w != width || h != height) {
    throw std::invalid_argument("texture level " + std::to_string(level) + " is " + std::to_string(w) + "x" +
                                std::to_string(h) + ", not " + std::to_string(width) + "x" + std::to_string(height));
  }
  std::vector<float> data(static_cast<std::size_t>(width) * height * channels);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture, level, format, GL_FLOAT, static_cast<GLsizei>(data.size() * sizeof(float)),
                    data.data());
  check_gl("read_texture");
  flip_rows(data, width, height, channels);
  return data;
}

Image to_image(std::vector<float> rgba, int width, int height) {
  Image img;
  img.width = width;
  img.height = height;
  img.rgba = std::move(rgba);
  return img;
}

}  // namespace

Image read_rgba(GLuint framebuffer, int width, int height, GLenum read_buffer) {
  return to_image(read_framebuffer(framebuffer, width, height, read_buffer, GL_RGBA, 4), width, height);
}
Image read_rgba(const GlFramebuffer& framebuffer, int width, int height, GLenum read_buffer) {
  return read_rgba(framebuffer.id(), width, height, read_buffer);
}
Image read_rgba_texture(GLuint texture, int width, int height, int level) {
  return to_image(read_texture(texture, width, height, level, GL_RGBA, 4), width, height);
}
Image read_rgba(const GlTexture& texture, int width, int height, int level) {
  return read_rgba_texture(texture.id(), width, height, level);
}

std::vector<float> read_red(GLuint framebuffer, int width, int height, GLenum read_buffer) {
  return read_framebuffer(framebuffer, width, height, read_buffer, GL_RED, 1);
}
std::vector<float> read_red(const GlFramebuffer& framebuffer, int width, int height, GLenum read_buffer) {
  return read_red(framebuffer.id(), width, height, read_buffer);
}
std::vector<float> read_rg(const GlFramebuffer& framebuffer, int width, int height, GLenum read_buffer) {
  return read_framebuffer(framebuffer.id(), width, height, read_buffer, GL_RG, 2);
}
std::vector<float> read_red_texture(GLuint texture, int width, int height, int level) {
  return read_texture(texture, width, height, level, GL_RED, 1);
}
std::vector<float> read_red(const GlTexture& texture, int width, int height, int level) {
  return read_red_texture(texture.id(), width, height, level);
}
std::vector<float> read_depth_texture(GLuint texture, int width, int height) {
  return read_texture(texture, width, height, 0, GL_DEPTH_COMPONENT, 1);
}

}  // namespace nimbus::render

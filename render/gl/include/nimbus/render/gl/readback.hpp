// Reading results back from the GPU: pixels as an Image or a float array, row 0 at the top.
#pragma once
#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/core/image.hpp"

namespace nimbus::render {

// RGBA float pixels of a framebuffer's color buffer (`read_buffer`: GL_COLOR_ATTACHMENTi; for
// framebuffer 0, GL_BACK) or of a texture's level, flipped so row 0 is the top (highest GL y).
// The read region is (0, 0)-(width, height). Bad sizes -> std::invalid_argument.
Image read_rgba(GLuint framebuffer, int width, int height, GLenum read_buffer = GL_COLOR_ATTACHMENT0);
Image read_rgba(const GlFramebuffer& framebuffer, int width, int height,
                GLenum read_buffer = GL_COLOR_ATTACHMENT0);
Image read_rgba_texture(GLuint texture, int width, int height, int level = 0);
Image read_rgba(const GlTexture& texture, int width, int height, int level = 0);

// The red channel alone (single-channel results), same layout and flip: width * height floats.
std::vector<float> read_red(GLuint framebuffer, int width, int height, GLenum read_buffer = GL_COLOR_ATTACHMENT0);
std::vector<float> read_red(const GlFramebuffer& framebuffer, int width, int height,
                            GLenum read_buffer = GL_COLOR_ATTACHMENT0);
std::vector<float> read_red_texture(GLuint texture, int width, int height, int level = 0);
std::vector<float> read_red(const GlTexture& texture, int width, int height, int level = 0);
// The red and green channels (two-channel results), same layout and flip: width * height * 2
// floats, interleaved.
std::vector<float> read_rg(const GlFramebuffer& framebuffer, int width, int height,
                           GLenum read_buffer = GL_COLOR_ATTACHMENT0);
// A depth texture's values in [0, 1], same layout and flip.
std::vector<float> read_depth_texture(GLuint texture, int width, int height);

}  // namespace nimbus::render

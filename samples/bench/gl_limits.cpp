// The device's rates for a frame's kinds of work (gl_limits.hpp).
#include "gl_limits.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"

namespace nimbus::cli {
namespace {

using Clock = std::chrono::steady_clock;

// A fragment's least work: a colour from its position.
const char* const kFill = R"(#version 450 core
in vec2 uv;
layout(location = 0) out vec4 colour;
void main() { colour = vec4(uv, 0.5, 0.25); }
)";

// kSamples trilinear samples along a short ray through the texture, summed.
constexpr int kSamples = 16;
const char* const kSample3d = R"(#version 450 core
in vec2 uv;
layout(location = 0) out vec4 colour;
layout(binding = 0) uniform sampler3D density;
void main() {
  float sum = 0.0;
  for (int i = 0; i < 16; ++i) sum += texture(density, vec3(uv, (float(i) + 0.5) / 16.0)).r;
  colour = vec4(sum, uv, 0.25);
}
)";

// A fragment that reads the other target's texel first, as a slice reads the light buffer that
// the slice before it wrote: the driver must finish that target before this pass reads it.
const char* const kDependent = R"(#version 450 core
in vec2 uv;
layout(location = 0) out vec4 colour;
layout(binding = 1) uniform sampler2D before;
void main() { colour = vec4(texelFetch(before, ivec2(0), 0).r + uv.x, uv.y, 0.5, 0.25); }
)";

double seconds_of(const auto& work) {
  glFinish();
  const auto t0 = Clock::now();
  work();
  glFinish();
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The slicer's round trip with almost no fragments: an 8x8 draw into the frame's RGBA32F target
// that reads the light buffer, then an 8x8 draw into a 256^2 R32F light buffer that reads the
// frame's target. What a slice costs beyond its fragments: the driver finishes each target
// before the other pass reads it (on llvmpipe, a scene rasterized per switch).
double slice_round_trips_per_s(const render::GlFramebuffer& eye_fb, const render::GlTexture& eye, const render::GlVertexArray& vao,
                               int width, int height, int repeats) {
  using namespace render;
  constexpr int kLight = 256, kTiny = 8, kTrips = 64;
  const GlTexture light = make_texture_2d(GL_R32F, kLight, kLight, TextureParams{GL_NEAREST, GL_NEAREST});
  const GlFramebuffer light_fb = make_framebuffer({{GL_COLOR_ATTACHMENT0, light.id()}});
  const ShaderProgram dependent =
      ShaderProgram::from_sources({{"bench_gl_dependent.frag.glsl", kDependent}}, {"fullscreen.vert.glsl", "bench_gl_dependent.frag.glsl"});
  dependent.use();
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  const auto trips = [&](int n) {
    for (int i = 0; i < n; ++i) {
      glBindFramebuffer(GL_FRAMEBUFFER, eye_fb.id());
      glViewport(0, 0, std::min(kTiny, width), std::min(kTiny, height));
      glBindTextureUnit(1, light.id());
      draw_fullscreen_triangle(vao);
      glBindFramebuffer(GL_FRAMEBUFFER, light_fb.id());
      glViewport(0, 0, kTiny, kTiny);
      glBindTextureUnit(1, eye.id());
      draw_fullscreen_triangle(vao);
    }
  };
  trips(2);  // compile and warm
  double s = 1e300;
  for (int r = 0; r < std::max(1, repeats); ++r) s = std::min(s, seconds_of([&] { trips(kTrips); }));
  glDisable(GL_BLEND);
  glViewport(0, 0, width, height);
  return kTrips / s;
}

}  // namespace

GlLimits measure_gl_limits(int width, int height, int repeats) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384) throw std::invalid_argument("gl limits: size must be in [1, 16384] per side");
  using namespace render;
  GlLimits out;
  out.width = width;
  out.height = height;
  out.device = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const GlTexture target = make_texture_2d(GL_RGBA32F, width, height, TextureParams{GL_NEAREST, GL_NEAREST});
  const GlFramebuffer fb = make_framebuffer({{GL_COLOR_ATTACHMENT0, target.id()}});
  const ShaderProgram fill =
      ShaderProgram::from_sources({{"bench_gl_fill.frag.glsl", kFill}}, {"fullscreen.vert.glsl", "bench_gl_fill.frag.glsl"});
  const ShaderProgram sample =
      ShaderProgram::from_sources({{"bench_gl_sample.frag.glsl", kSample3d}}, {"fullscreen.vert.glsl", "bench_gl_sample.frag.glsl"});
  // The clouds' density format, at a size a keyframe pair's texture has.
  constexpr int kTex = 128;
  const GlTexture density = make_texture_3d(GL_R16F, kTex, kTex, kTex);
  {
    std::vector<float> texels(static_cast<std::size_t>(kTex) * kTex * kTex);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<float>((i * 2654435761u) % 1000u) * 1e-3f;
    glTextureSubImage3D(density.id(), 0, 0, 0, 0, kTex, kTex, kTex, GL_RED, GL_FLOAT, texels.data());
  }
  const GlVertexArray vao = make_vertex_array();
  glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  const double pixels = static_cast<double>(width) * height;
  constexpr int kDraws = 24;
  const auto draws = [&](const ShaderProgram& p, int n) {
    p.use();
    for (int i = 0; i < n; ++i) draw_fullscreen_triangle(vao);
  };
  const auto best = [&](const auto& work) {
    double s = 1e300;
    for (int r = 0; r < std::max(1, repeats); ++r) s = std::min(s, seconds_of(work));
    return s;
  };
  draws(fill, 2);  // compile and warm
  draws(sample, 2);
  glDisable(GL_BLEND);
  const double fill_s = best([&] { draws(fill, kDraws); });
  out.fragments_per_s = pixels * kDraws / fill_s;
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over", as the slices blend
  out.blended_per_s = pixels * kDraws / best([&] { draws(fill, kDraws); });
  glDisable(GL_BLEND);
  glBindTextureUnit(0, density.id());
  const double sample_s = best([&] { draws(sample, kDraws); });
  out.samples_3d_per_s = pixels * kDraws * kSamples / std::max(sample_s - fill_s, 1e-9);
  out.slice_round_trips_per_s = slice_round_trips_per_s(fb, target, vao, width, height, repeats);
  glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
  std::vector<float> pixels_back(static_cast<std::size_t>(pixels) * 4);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  constexpr int kReads = 8;
  const double read_s = best([&] {
    for (int i = 0; i < kReads; ++i) glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, pixels_back.data());
  });
  out.readback_pixels_per_s = pixels * kReads / read_s;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("measure_gl_limits");
  return out;
}

}  // namespace nimbus::cli

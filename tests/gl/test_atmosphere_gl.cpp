// The shaders read the physical sky's tables as the CPU does (shaders/lib/sky.glsl,
// lib/aerial_perspective.glsl against atmosphere_tables.hpp's lookups): a probe shader evaluates
// the sky's radiance and the aerial perspective over a grid of directions, the CPU the same.
#include <gtest/gtest.h>

#include <cmath>

#include "nimbus/render/media/atmosphere_tables.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/atmosphere_textures.hpp"
#include "nimbus/render/gl/readback.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

constexpr int kW = 48, kH = 24;

// Pixel (x, y): azimuth 360 (x + 1/2) / W degrees, elevation from -20 to 86 degrees.
glm::dvec3 probe_dir(double x, double y) {
  const double az = 2.0 * M_PI * x / kW, el = (-20.0 + 106.0 * y / kH) * M_PI / 180.0;
  return {std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az)};
}

const char* kProbe = R"(#version 450 core
#include "lib/contract.glsl"
#include "lib/sky.glsl"
#include "lib/aerial_perspective.glsl"
uniform int u_what;          // 0 sky radiance, 1 aerial in-scattering, 2 aerial transmittance
uniform float u_distance_m;
layout(location = 0) out vec4 o;
void main() {
  vec2 p = gl_FragCoord.xy;  // pixel centres
  float az = 2.0 * 3.14159265358979 * p.x / 48.0, el = (-20.0 + 106.0 * p.y / 24.0) * 3.14159265358979 / 180.0;
  vec3 dir = vec3(cos(el) * cos(az), sin(el), cos(el) * sin(az));
  vec3 S, T;
  aerial_perspective(dir, u_distance_m, S, T);
  o = vec4(u_what == 0 ? sky_radiance(dir) : (u_what == 1 ? S : T), 1.0);
}
)";

TEST(AtmosphereGl, ShadersReadTheTablesAsTheCpu) {
  NIMBUS_REQUIRE_GL();
  const double e = 20.0 * M_PI / 180.0;
  const auto tables = build_atmosphere_tables(Atmosphere{}, AtmosphereView{2.0, {std::cos(e), std::sin(e), 0.3}, 40000.0});
  const AtmosphereTextures tex = upload_atmosphere(tables);
  GlTexture target = make_texture_2d(GL_RGBA32F, kW, kH, TextureParams{GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 1});
  GlFramebuffer fbo = make_framebuffer({{GL_COLOR_ATTACHMENT0, target.id()}});
  ShaderProgram p = ShaderProgram::from_sources({{"atmosphere_probe.frag.glsl", kProbe}}, {"fullscreen.vert.glsl", "atmosphere_probe.frag.glsl"});
  UniformBuffer<SkyBlock> sky;  // a physical sky with no gradient: what the tables give
  sky.update(sky_block(nullptr, &tex));
  sky.bind(contract::BLOCK_SKY);
  bind_atmosphere_textures(tex);
  GlVertexArray vao = make_vertex_array();
  for (int what = 0; what < 3; ++what) {
    for (double distance : {0.0, 3000.0, 25000.0, 90000.0}) {
      if (what == 0 && distance > 0.0) continue;
      p.set("u_what", what);
      p.set("u_distance_m", static_cast<float>(distance));
      glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
      glViewport(0, 0, kW, kH);
      p.use();
      draw_fullscreen_triangle(vao);
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      const Image gpu = read_rgba(target, kW, kH);
      double worst = 0.0;
      for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
          const glm::dvec3 d = probe_dir(x + 0.5, y + 0.5);
          const AerialPerspective ap = table_aerial_perspective(*tables, d, distance);
          const glm::dvec3 want = what == 0 ? table_sky_radiance(*tables, d) : (what == 1 ? ap.inscattered_w_sr_m2 : ap.transmittance);
          // read_rgba returns rows top-down: GL row y is image row kH - 1 - y
          const float* got = &gpu.rgba[(static_cast<std::size_t>(kH - 1 - y) * kW + x) * 4];
          for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(got[c]));
            const double scale = what == 0 ? want[c] : std::max(want[c], 1e-3 * tables->sky_mean_radiance_w_sr_m2[c]);
            worst = std::max(worst, scale > 0.0 ? std::abs(got[c] - want[c]) / scale : std::abs(got[c] - want[c]));
          }
        }
      }
      // The sky view: the same texels and weights, float rounding only. The aerial tables go
      // through the unit's trilinear filter (8-bit weights on llvmpipe): at most 1/256 of a step.
      EXPECT_LT(worst, what == 0 ? 2e-3 : 1e-2) << "what " << what << " distance " << distance;
    }
  }
}

}  // namespace
}  // namespace nimbus::render

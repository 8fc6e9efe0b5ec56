// The surface airlight (lib/surface_airlight.glsl) read from its table as an R32F texture on
// UNIT_SURFACE_AIRLIGHT (nx wide over ln Tsp, ny high over theta_s), interpolated here in float
// with texelFetch (the fixed-point weights of hardware filtering would add their own error).
// GLSL only.
#ifndef NIMBUS_SURFACE_AIRLIGHT_TEXTURE_GLSL
#define NIMBUS_SURFACE_AIRLIGHT_TEXTURE_GLSL

#include "lib/surface_airlight.glsl"

layout(binding = UNIT_SURFACE_AIRLIGHT) uniform sampler2D u_surface_airlight_table;

// L_p,a per unit albedo at a point Dsp from a light of intensity I0, cos theta_s between the
// normal and the direction to the light.
float surface_airlight(float sigma_t, float sigma_s, float I0, float Dsp, float cos_theta_s) {
  ivec2 size = textureSize(u_surface_airlight_table, 0);
  vec2 f = surface_airlight_coords(max(sigma_t, 0.0) * max(Dsp, 1.0e-20), cos_theta_s, size.x, size.y);
  ivec2 c = surface_airlight_cell(f, size.x, size.y);
  float g00 = texelFetch(u_surface_airlight_table, c, 0).r;
  float g10 = texelFetch(u_surface_airlight_table, c + ivec2(1, 0), 0).r;
  float g01 = texelFetch(u_surface_airlight_table, c + ivec2(0, 1), 0).r;
  float g11 = texelFetch(u_surface_airlight_table, c + ivec2(1, 1), 0).r;
  return surface_airlight_radiance(sigma_t, sigma_s, I0, Dsp, surface_airlight_bilinear(f, c, g00, g10, g01, g11));
}

#endif

// The scene's sky (scene.hpp Sky): where rays that meet no surface end, and its radiance: a
// gradient from the horizon to the zenith, or the physical sky's sky-view table
// (atmosphere_tables.hpp), read through the same map and the same bilinear weights as the CPU.
#include "lib/atmosphere_map.glsl"
#include "lib/sky_block.glsl"
layout(binding = UNIT_SKY_VIEW) uniform sampler2D u_sky_view;  // RGBA32F, ATM_SKY_W x ATM_SKY_H

// Texel coordinates of a view direction in the sky-view and aerial-perspective maps (as
// table_sky_radiance: the azimuth from the sun's, the zenith angle).
vec2 sky_view_uv(vec3 dir) {
  vec2 sh = vec2(sky_state.sun.x, sky_state.sun.z), dh = vec2(dir.x, dir.z);
  float ls = length(sh), ld = length(dh);
  float cos_phi = (ls > 1.0e-9 && ld > 1.0e-9) ? dot(sh, dh) / (ls * ld) : 1.0;
  return atm_view_uv(cos_phi, clamp(dir.y, -1.0, 1.0), sky_state.cos_horizon);
}

// Bilinear, clamped, texel centres on the ends (AtmosphereTable::bilinear).
vec3 sky_table_bilinear(vec2 c) {
  ivec2 size = textureSize(u_sky_view, 0);
  vec2 x = clamp(c, vec2(0.0), vec2(size - 1));
  ivec2 i0 = min(ivec2(x), size - 1), i1 = min(i0 + 1, size - 1);
  vec2 f = x - vec2(i0);
  vec3 a = mix(texelFetch(u_sky_view, i0, 0).rgb, texelFetch(u_sky_view, ivec2(i1.x, i0.y), 0).rgb, f.x);
  vec3 b = mix(texelFetch(u_sky_view, ivec2(i0.x, i1.y), 0).rgb, texelFetch(u_sky_view, i1, 0).rgb, f.x);
  return mix(a, b, f.y);
}

vec3 sky_radiance(vec3 dir) {
  if (sky_state.physical != 0) {
    return sky_table_bilinear(sky_view_uv(dir) * vec2(float(ATM_SKY_W - 1), float(ATM_SKY_H - 1)));
  }
  return sky_state.horizon + (sky_state.zenith - sky_state.horizon) * sqrt(max(dir.y, 0.0));
}

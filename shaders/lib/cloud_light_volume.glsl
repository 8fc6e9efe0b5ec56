// The light volume (render/core light_volume.hpp) as the slicer's eye pass reads it: the radiance
// that once-or-more scattered sunlight in-scatters toward the eye, per unit irradiance and per
// unit scattering coefficient, with the radiance cut after l = 2 (docs/clouds.md eq. MS-1):
//   phi / (4 pi) (1 + 3 p_1 F.w_o / mean(phi) + (15 / 2) p_2 w_o^T Q w_o / mean(phi)), >= 0,
// p_l = w g_forward^l + (1 - w) g_back^l (as light_volume_inscatter). One RGBA32F 3D texture,
// three times as wide as the grid: (fluence RGB, Q xx), (flux xyz, Q yy), (Q xy, xz, yz, 0) in
// its thirds along x; lookups are clamped to the texel centres of one third, so the thirds never
// blend (as light_volume_inscatter clamps to the edge cells).
#ifndef NIMBUS_CLOUD_LIGHT_VOLUME_GLSL
#define NIMBUS_CLOUD_LIGHT_VOLUME_GLSL
#include "lib/cloud_block.glsl"
layout(binding = UNIT_LIGHT_VOLUME) uniform sampler3D u_light_volume;
uniform vec3 u_lv_world_min;   // the grid's corner, metres
uniform vec3 u_lv_cell_m;      // a cell's sides, metres per axis
uniform vec3 u_lv_cells;       // cells per axis

vec3 light_volume_inscatter(vec3 world, vec3 to_eye) {
  vec3 texel = clamp((world - u_lv_world_min) / u_lv_cell_m, vec3(0.5), u_lv_cells - 0.5);
  vec3 tc = texel / vec3(3.0 * u_lv_cells.x, u_lv_cells.yz);
  float third = 1.0 / 3.0;
  vec4 a = textureLod(u_light_volume, tc, 0.0);                          // fluence RGB, Q xx
  vec4 b = textureLod(u_light_volume, tc + vec3(third, 0.0, 0.0), 0.0);  // flux xyz, Q yy
  vec3 c = textureLod(u_light_volume, tc + vec3(2.0 * third, 0.0, 0.0), 0.0).xyz;  // Q xy, xz, yz
  float mean = (a.r + a.g + a.b) / 3.0;
  if (!(mean > 0.0)) return vec3(0.0);
  vec3 w = to_eye;
  float wqw = a.w * w.x * w.x + b.w * w.y * w.y - (a.w + b.w) * w.z * w.z +
              2.0 * (c.x * w.x * w.y + c.y * w.x * w.z + c.z * w.y * w.z);
  vec3 g = cloud.phase;  // g_forward, g_back, forward weight
  float p1 = mix(g.y, g.x, g.z);
  float p2 = mix(g.y * g.y, g.x * g.x, g.z);
  float directional = (3.0 * p1 * dot(b.xyz, w) + 7.5 * p2 * wqw) / mean;
  return max(a.rgb * (1.0 + directional) * (1.0 / (4.0 * 3.14159265358979)), vec3(0.0));
}
#endif

// The light volume (render/core light_volume.hpp) as the slicer's eye pass reads it: the radiance
// that once-or-more scattered sunlight in-scatters toward the eye, per unit irradiance and per
// unit scattering coefficient, in the P1 approximation (docs/clouds.md eq. MS-1):
//   (phi + 3 g F.w_o) / (4 pi), the flux term scaled per channel by phi_c / mean(phi), >= 0.
// One RGBA32F 3D texture, twice as wide as the grid: fluence RGB in its first half along x, flux
// xyz in its second; lookups are clamped to the texel centres of one half, so the halves never
// blend (as light_volume_inscatter clamps to the edge cells).
#ifndef NIMBUS_CLOUD_LIGHT_VOLUME_GLSL
#define NIMBUS_CLOUD_LIGHT_VOLUME_GLSL
#include "lib/cloud_block.glsl"
layout(binding = UNIT_LIGHT_VOLUME) uniform sampler3D u_light_volume;
uniform vec3 u_lv_world_min;   // the grid's corner, metres
uniform float u_lv_cell_m;     // cube cells, metres per side
uniform vec3 u_lv_cells;       // cells per axis

vec3 light_volume_inscatter(vec3 world, vec3 to_eye) {
  vec3 texel = clamp((world - u_lv_world_min) / u_lv_cell_m, vec3(0.5), u_lv_cells - 0.5);
  vec3 tc = texel / vec3(2.0 * u_lv_cells.x, u_lv_cells.yz);
  vec3 phi = textureLod(u_light_volume, tc, 0.0).rgb;
  vec3 flux = textureLod(u_light_volume, tc + vec3(0.5, 0.0, 0.0), 0.0).rgb;
  float mean = (phi.r + phi.g + phi.b) / 3.0;
  float g = mix(cloud.phase.y, cloud.phase.x, cloud.phase.z);  // w g_forward + (1 - w) g_back
  float directional = mean > 0.0 ? 3.0 * g * dot(flux, to_eye) / mean : 0.0;
  return max(phi * (1.0 + directional) * (1.0 / (4.0 * 3.14159265358979)), vec3(0.0));
}
#endif

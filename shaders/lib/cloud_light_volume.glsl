// The light volume (render/core light_volume.hpp) as the slicer's eye pass reads it: the radiance
// that once-or-more scattered sunlight in-scatters toward the eye, per unit irradiance and per
// unit scattering coefficient (docs/clouds.md eqs. MS-1 and MS-3): scattering orders 1 and 2 as
// Henyey-Greenstein lobes f_k phi HG(mu_k) about the sun's direction s, which in-scatter
// f_k phi sum_i w_i HG(g_i mu_k; w_o.s), and the rest cut after l = 2,
//   phi / (4 pi) (1 - sum f_k + 3 p_1 (F.w_o / mean(phi) - sum f_k mu_k w_o.s)
//                + (15 / 2) p_2 (w_o^T Q w_o / mean(phi) - sum f_k mu_k^2 ((w_o.s)^2 - 1 / 3))), >= 0,
// p_l = w g_forward^l + (1 - w) g_back^l (as light_volume_inscatter), all scaled by eq. MS-4's
// fitted fluence over the interpolated one. One RGBA32F 3D texture, five times as wide as the
// grid: (fluence RGB, Q xx), (flux xyz, Q yy), (Q xy, xz, yz, h), (gradient xyz, 0),
// (f_1, mu_1, f_2, mu_2) in its fifths along x; lookups are clamped to the texel centres of one
// fifth, so the fifths never blend (as light_volume_inscatter clamps to the edge cells).
#ifndef NIMBUS_CLOUD_LIGHT_VOLUME_GLSL
#define NIMBUS_CLOUD_LIGHT_VOLUME_GLSL
#include "lib/cloud_block.glsl"
#include "lib/cloud_phase.glsl"
layout(binding = UNIT_LIGHT_VOLUME) uniform sampler3D u_light_volume;
uniform vec3 u_lv_world_min;   // the grid's corner, metres
uniform vec3 u_lv_cell_m;      // a cell's sides, metres per axis
uniform vec3 u_lv_cells;       // cells per axis
uniform vec3 u_lv_light_dir;   // the sun's direction of propagation, unit (the lobes' axis)

vec3 light_volume_inscatter(vec3 world, vec3 to_eye) {
  vec3 u = clamp((world - u_lv_world_min) / u_lv_cell_m, vec3(0.0), u_lv_cells);  // cells from the corner
  vec3 tc = clamp(u, vec3(0.5), u_lv_cells - 0.5) / vec3(5.0 * u_lv_cells.x, u_lv_cells.yz);
  float fifth = 0.2;
  vec4 a = textureLod(u_light_volume, tc, 0.0);                          // fluence RGB, Q xx
  vec4 b = textureLod(u_light_volume, tc + vec3(fifth, 0.0, 0.0), 0.0);  // flux xyz, Q yy
  vec4 c = textureLod(u_light_volume, tc + vec3(2.0 * fifth, 0.0, 0.0), 0.0);      // Q xy, xz, yz, h
  vec3 grad = textureLod(u_light_volume, tc + vec3(3.0 * fifth, 0.0, 0.0), 0.0).xyz;  // gradient
  vec4 d = textureLod(u_light_volume, tc + vec3(4.0 * fifth, 0.0, 0.0), 0.0);      // f_1, mu_1, f_2, mu_2
  float mean = (a.r + a.g + a.b) / 3.0;
  if (!(mean > 0.0)) return vec3(0.0);
  float fit = max(mean + dot(grad, u) - c.w, 0.0) / mean;  // eq. MS-4
  vec3 w = to_eye;
  float ws = dot(w, u_lv_light_dir);
  float wqw = a.w * w.x * w.x + b.w * w.y * w.y - (a.w + b.w) * w.z * w.z +
              2.0 * (c.x * w.x * w.y + c.y * w.x * w.z + c.z * w.y * w.z);
  vec3 g = cloud.phase;  // g_forward, g_back, forward weight
  float p1 = mix(g.y, g.x, g.z);
  float p2 = mix(g.y * g.y, g.x * g.x, g.z);
  // The lobes: HG(g_i) convolved with HG(mu_k) is HG(g_i mu_k).
  float lobe = 4.0 * 3.14159265358979 *
               (d.x * cloud_dual_phase(vec3(g.xy * d.y, g.z), ws) + d.z * cloud_dual_phase(vec3(g.xy * d.w, g.z), ws));
  float harmonic = 1.0 - d.x - d.z +
                   3.0 * p1 * (dot(b.xyz, w) / mean - (d.x * d.y + d.z * d.w) * ws) +
                   7.5 * p2 * (wqw / mean - (d.x * d.y * d.y + d.z * d.w * d.w) * (ws * ws - 1.0 / 3.0));
  return a.rgb * (fit * (max(harmonic, 0.0) + lobe) * (1.0 / (4.0 * 3.14159265358979)));
}
#endif

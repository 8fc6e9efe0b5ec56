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
#include "lib/cloud_phase.glsl"
layout(binding = UNIT_LIGHT_VOLUME) uniform sampler3D u_light_volume;
// The grid (uniform_blocks.hpp's LightVolumeBlock).
layout(std140, binding = BLOCK_LIGHT_VOLUME) uniform LightVolumeBlock {
  vec3 world_min;  // the grid's corner, metres
  vec3 cell_m;     // a cell's sides, metres per axis
  vec3 cells;      // cells per axis
  vec3 light_dir;  // the sun's direction of propagation, unit (the lobes' axis)
} lv_grid;

struct LightVolumeCell {
  vec4 a;     // fluence RGB, Q xx
  vec4 b;     // flux xyz, Q yy
  vec4 c;     // Q xy, xz, yz, h
  vec3 grad;  // the fluence's gradient
  vec4 d;     // f_1, mu_1, f_2, mu_2
};

// The volume's values at u (cells from the corner), interpolated.
LightVolumeCell light_volume_at(vec3 u) {
  vec3 tc = clamp(u, vec3(0.5), lv_grid.cells - 0.5) / vec3(5.0 * lv_grid.cells.x, lv_grid.cells.yz);
  float fifth = 0.2;
  LightVolumeCell v;
  v.a = textureLod(u_light_volume, tc, 0.0);
  v.b = textureLod(u_light_volume, tc + vec3(fifth, 0.0, 0.0), 0.0);
  v.c = textureLod(u_light_volume, tc + vec3(2.0 * fifth, 0.0, 0.0), 0.0);
  v.grad = textureLod(u_light_volume, tc + vec3(3.0 * fifth, 0.0, 0.0), 0.0).xyz;
  v.d = textureLod(u_light_volume, tc + vec3(4.0 * fifth, 0.0, 0.0), 0.0);
  return v;
}

// One cell's own values (cell in [0, cells)).
LightVolumeCell light_volume_cell(ivec3 cell) {
  ivec3 step = ivec3(int(lv_grid.cells.x), 0, 0);
  LightVolumeCell v;
  v.a = texelFetch(u_light_volume, cell, 0);
  v.b = texelFetch(u_light_volume, cell + step, 0);
  v.c = texelFetch(u_light_volume, cell + 2 * step, 0);
  v.grad = texelFetch(u_light_volume, cell + 3 * step, 0).xyz;
  v.d = texelFetch(u_light_volume, cell + 4 * step, 0);
  return v;
}

// The angular part: (harmonics cut after l = 2, >= 0, + the lobes) / (4 pi), toward to_eye.
// mean > 0. phase: the cloud's (g_forward, g_back, forward weight), CloudBlock.phase.
float light_volume_angular(LightVolumeCell v, float mean, vec3 to_eye, vec3 phase) {
  vec3 w = to_eye;
  float ws = dot(w, lv_grid.light_dir);
  float wqw = v.a.w * w.x * w.x + v.b.w * w.y * w.y - (v.a.w + v.b.w) * w.z * w.z +
              2.0 * (v.c.x * w.x * w.y + v.c.y * w.x * w.z + v.c.z * w.y * w.z);
  vec3 g = phase;  // g_forward, g_back, forward weight
  float p1 = mix(g.y, g.x, g.z);
  float p2 = mix(g.y * g.y, g.x * g.x, g.z);
  vec4 d = v.d;
  // The lobes: HG(g_i) convolved with HG(mu_k) is HG(g_i mu_k).
  float lobe = 4.0 * 3.14159265358979 *
               (d.x * cloud_dual_phase(vec3(g.xy * d.y, g.z), ws) + d.z * cloud_dual_phase(vec3(g.xy * d.w, g.z), ws));
  float harmonic = 1.0 - d.x - d.z +
                   3.0 * p1 * (dot(v.b.xyz, w) / mean - (d.x * d.y + d.z * d.w) * ws) +
                   7.5 * p2 * (wqw / mean - (d.x * d.y * d.y + d.z * d.w * d.w) * (ws * ws - 1.0 / 3.0));
  return (max(harmonic, 0.0) + lobe) * (1.0 / (4.0 * 3.14159265358979));
}

vec3 light_volume_inscatter(vec3 world, vec3 to_eye, vec3 phase) {
  vec3 u = clamp((world - lv_grid.world_min) / lv_grid.cell_m, vec3(0.0), lv_grid.cells);  // cells from the corner
  LightVolumeCell v = light_volume_at(u);
  float mean = (v.a.r + v.a.g + v.a.b) / 3.0;
  if (!(mean > 0.0)) return vec3(0.0);
  float fit = max(mean + dot(v.grad, u) - v.c.w, 0.0) / mean;  // eq. MS-4
  return v.a.rgb * (fit * light_volume_angular(v, mean, to_eye, phase));
}

// The same radiance with its angular part made once per frame at the cell centres toward the
// eye (light_volume_radiance.comp.glsl, for the clouds' one phase): two fetches instead of five.
// Two halves along x: (fluence RGB x angular part, mean fluence) and (gradient, mean - h), so eq.
// MS-4's fit within a cell is exactly light_volume_inscatter's, and only the angular part is
// interpolated between cell centres (the eye's direction varies little across a cell seen from
// outside it). The eye pass reads it with MS_VOLUME 2.
layout(binding = UNIT_LIGHT_RADIANCE) uniform sampler3D u_light_radiance;
uniform vec3 u_lr_phase;  // the phase it is made for (the comp shader's)

vec3 light_volume_radiance(vec3 world) {
  vec3 u = clamp((world - lv_grid.world_min) / lv_grid.cell_m, vec3(0.0), lv_grid.cells);
  vec3 tc = clamp(u, vec3(0.5), lv_grid.cells - 0.5) / vec3(2.0 * lv_grid.cells.x, lv_grid.cells.yz);
  vec4 lit = textureLod(u_light_radiance, tc, 0.0);
  vec4 fit = textureLod(u_light_radiance, tc + vec3(0.5, 0.0, 0.0), 0.0);
  if (!(lit.a > 0.0)) return vec3(0.0);
  return lit.rgb * (max(fit.w + dot(fit.xyz, u), 0.0) / lit.a);  // eq. MS-4
}
#endif

#version 450 core
// The light-shaft pass: per pixel, the attenuated surface radiance (thesis eq. 23) plus the
// single-scattered airlight of every light, by one of three methods chosen at compile time
// (METHOD, a SHAFT_METHOD_* code of lib/contract.glsl):
//   SHAFT_METHOD_RAYMARCH: ray marching with shadow-map visibility and a per-pixel jitter
//             (thesis 4.1, Alg. 1)
//   SHAFT_METHOD_ANALYTIC: the analytic airlight of Sun et al. (eqs. 7-12), no volumetric shadows
//   SHAFT_METHOD_SHADOW_VOLUME: shadow-volume intervals (thesis 4.3, Biri et al. eqs. 10-12):
//             closed form on the parts of the ray before the nearest and after the farthest
//             shadow-volume crossing, STEPS samples only in between.
// Defines: METHOD, STEPS, AIRLIGHT_TABLE (1: Sun's F table for the analytic method, else the
// stable form).
#include "lib/contract.glsl"
#ifndef METHOD
#define METHOD SHAFT_METHOD_RAYMARCH
#endif
#ifndef STEPS
#define STEPS 64
#endif
#ifndef AIRLIGHT_TABLE
#define AIRLIGHT_TABLE 0
#endif
in vec2 uv;
layout(binding = UNIT_SURFACE_RADIANCE) uniform sampler2D u_surface_radiance;  // RGBA32F: radiance leaving the surface, alpha 1 on hits
layout(binding = UNIT_SCENE_DISTANCE) uniform sampler2D u_surface_distance;  // R32F: metres from the eye, 0 where nothing was hit
uniform float u_sigma_t;    // extinction, per metre
uniform float u_sigma_s;    // scattering, per metre
uniform int u_phase_kind;   // PHASE_* code
uniform float u_phase_g;
// The pass's own values (uniform_blocks.hpp's ShaftPassBlock).
layout(std140, binding = BLOCK_SHAFT_PASS) uniform ShaftPassBlock {
  float march_cutoff_m;    // ray-march end for rays that hit nothing
  float shadow_ceiling_m;  // no shadow of the sun (opaque or cloud) above this height; 1e30 = none known
  int jitter_mode;         // JITTER_* code
  float jitter_shift;      // this frame's shift of the jitter values, modulo 1
  int f_table_size;        // the F table's size (AIRLIGHT_TABLE)
} shaft_pass;
layout(binding = UNIT_JITTER) uniform sampler2D u_jitter;  // tiled jitter values in [0, 1)
#include "lib/camera_ray.glsl"
#include "lib/lights.glsl"
#include "lib/phase.glsl"
#include "lib/sky.glsl"
#include "lib/airlight.glsl"
#include "lib/lamp_airlight.glsl"
#if METHOD == SHAFT_METHOD_ANALYTIC && AIRLIGHT_TABLE
#include "lib/airlight_table.glsl"
layout(binding = UNIT_F_TABLE) uniform sampler2D u_F_table;
#endif
#if METHOD == SHAFT_METHOD_SHADOW_VOLUME
layout(binding = UNIT_SV_NEAR) uniform sampler2DArray u_sv_near;  // layer = point light index, last layer = sun
layout(binding = UNIT_SV_FAR) uniform sampler2DArray u_sv_far;
#endif
layout(location = 0) out vec4 o_color;

const float INF_M = 1.0e30;

float hash_jitter(uvec2 p) {
  uint h = p.x * 1664525u + p.y * 1013904223u;
  h ^= h >> 16; h *= 0x7feb352du; h ^= h >> 15; h *= 0x846ca68bu; h ^= h >> 16;
  return float(h >> 8) * (1.0 / 16777216.0);
}

float pixel_jitter(ivec2 px) {
  if (shaft_pass.jitter_mode == JITTER_WHITE) return fract(hash_jitter(uvec2(px)) + shaft_pass.jitter_shift);
  if (shaft_pass.jitter_mode == JITTER_BLUE_NOISE) {
    ivec2 size = textureSize(u_jitter, 0);
    return fract(texelFetch(u_jitter, ivec2(px.x % size.x, px.y % size.y), 0).r + shaft_pass.jitter_shift);
  }
  return 0.5;
}

// Ray-marched single scattering from lamp i over [a, b] (thesis eq. 26): n samples at
// a + (k + jitter) (b - a) / n, each weighted by the shadow-map visibility and a spot's cone.
float march_point(int i, vec3 dir, float a, float b, int n, float jitter) {
  float h = (b - a) / float(n);
  float sum = 0.0;
  for (int k = 0; k < n; ++k) {
    float x = a + (float(k) + jitter) * h;
    vec3 p = camera.eye + dir * x;
    vec3 lv = p - lights.lamp[i].position.xyz;
    float d = length(lv);
    float vis = point_visibility(i, p);
    if (vis > 0.0)
      sum += phase_value(u_phase_kind, u_phase_g, dot(lv / d, -dir)) * lamp_spot_weight(i, lv / d) *
             exp(-u_sigma_t * (d + x)) / (d * d);
  }
  return u_sigma_s * sum * h;
}

float march_sun(vec3 dir, float a, float b, int n, float jitter) {
  float h = (b - a) / float(n);
  float sum = 0.0;
  for (int k = 0; k < n; ++k) {
    float x = a + (float(k) + jitter) * h;
    sum += sun_light_visibility(camera.eye + dir * x) * exp(-u_sigma_t * x);
  }
  return u_sigma_s * phase_value(u_phase_kind, u_phase_g, dot(-lights.sun.position.xyz, -dir)) * sum * h;
}

// Unshadowed airlight of lamp i over [x0, x1]: closed form, or a spot's quadrature.
float closed_point(int i, vec3 dir, float x0, float x1) {
  return lamp_segment_airlight(i, camera.eye, dir, x0, x1, u_sigma_t, u_sigma_s, u_phase_kind, u_phase_g);
}

#if METHOD == SHAFT_METHOD_ANALYTIC && AIRLIGHT_TABLE
// Sun's table form of lamp i's airlight up to the surface at Dvp (INF_M: none), for albedo 1
// (beta = sigma_s = sigma_t) scaled by the albedo. The table is for lamps that shine every way,
// and Sun's formula as printed is undefined where A1 = Tsv sin(gamma) = 0 (no fog, or the light
// on the ray's line): a spot, and those places, take closed_point, so no NaN reaches the image.
float table_point(int i, vec3 dir, float t_end, float Dvp) {
  if (lamp_is_spot(i)) return closed_point(i, dir, 0.0, t_end);
  vec3 to_light = lights.lamp[i].position.xyz - camera.eye;
  float Dsv = length(to_light);
  float cg = clamp(dot(dir, to_light) / Dsv, -1.0, 1.0);
  float sg = min(length(cross(dir, to_light)) / Dsv, 1.0);
  float a = (u_sigma_t > 0.0 ? u_sigma_s / u_sigma_t : 0.0) *
            airlight_table(u_F_table, shaft_pass.f_table_size, u_sigma_t, 1.0, Dsv, Dvp, cg, sg);
  return (isnan(a) || isinf(a)) ? closed_point(i, dir, 0.0, t_end) : a;
}
#endif

float closed_sun(vec3 dir, float x0, float x1) {
  return sun_segment_airlight(u_sigma_t, u_sigma_s, 1.0, dot(-lights.sun.position.xyz, -dir), x0, x1, u_phase_kind, u_phase_g);
}

// The part [lo, hi] of [a, b] below the shadow ceiling (lo > hi: none). Above it the sun (above
// the horizon) meets no occluder and no cloud, so the airlight there has its closed form.
vec2 shadowed_span(vec3 dir, float a, float b) {
  float y0 = camera.eye.y - shaft_pass.shadow_ceiling_m;  // < 0: the eye is below the ceiling
  float dy = dir.y;
  float cross_t = -y0 / (abs(dy) > 1.0e-12 ? dy : 1.0e-12);  // where the ray meets the ceiling
  float lo = a, hi = b;
  if (y0 <= 0.0 && dy > 0.0) hi = min(b, cross_t);
  if (y0 > 0.0) lo = dy < 0.0 ? max(a, cross_t) : b + 1.0;
  return vec2(lo, hi);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec3 Ls = texelFetch(u_surface_radiance, px, 0).rgb;
  float t = texelFetch(u_surface_distance, px, 0).r;
  bool hit = t > 0.0;
  bool sky = !hit && sky_state.has_sky != 0;
  // The fog ends at the sky (scene.hpp Sky): a surface beyond it, the ground toward the
  // horizon, is seen through the sky's distance of fog.
  float t_end = hit ? (sky_state.has_sky != 0 ? min(t, sky_state.distance_m) : t) : (sky ? sky_state.distance_m : INF_M);
  vec3 dir = pixel_ray_dir(gl_FragCoord.xy);
  vec3 L = hit ? Ls * exp(-u_sigma_t * t_end) : (sky ? sky_radiance(dir) * exp(-u_sigma_t * t_end) : vec3(0.0));
  float jitter = pixel_jitter(px);
  float t_march = hit ? t_end : (sky ? min(sky_state.distance_m, shaft_pass.march_cutoff_m) : shaft_pass.march_cutoff_m);

  for (int i = 0; i < lights.lamp_count; ++i) {
#if METHOD == SHAFT_METHOD_RAYMARCH
    float a = march_point(i, dir, 0.0, t_march, STEPS, jitter);
#elif METHOD == SHAFT_METHOD_ANALYTIC
#if AIRLIGHT_TABLE
    float a = table_point(i, dir, t_end, hit ? t_end : INF_M);
#else
    float a = closed_point(i, dir, 0.0, t_end);
#endif
#else
    float tn = texelFetch(u_sv_near, ivec3(px, i), 0).r;
    float tf = texelFetch(u_sv_far, ivec3(px, i), 0).r;
    float a = 0.0;
    if (tn >= 1.0e29) {  // no shadow-volume crossing before the surface: one state
      // Two probes; where they disagree a boundary slipped between the skirts (a silhouette
      // grazed within a texel), and the whole ray is sampled instead.
      float v0 = point_visibility(i, camera.eye + dir * (0.5 * min(t_end, 10.0)));
      float v1 = point_visibility(i, camera.eye + dir * (0.999 * t_march));
      if (v0 != v1) a = march_point(i, dir, 0.0, t_march, STEPS, jitter);
      else if (v0 > 0.0) a = closed_point(i, dir, 0.0, t_end);
    } else {
      if (point_visibility(i, camera.eye + dir * (0.5 * tn)) > 0.0) a += closed_point(i, dir, 0.0, tn);
      a += march_point(i, dir, tn, tf, STEPS, jitter);
      float probe = tf + 0.5 * (min(t_end, tf + 10.0) - tf);
      if (point_visibility(i, camera.eye + dir * probe) > 0.0) a += closed_point(i, dir, tf, t_end);
    }
#endif
    L += lights.lamp[i].power.rgb * a;
  }

  if (lights.has_sun != 0) {
#if METHOD == SHAFT_METHOD_RAYMARCH
    // Samples only where a shadow can fall; the closed form before and after.
    vec2 span = shadowed_span(dir, 0.0, t_march);
    float a = span.x < span.y ? march_sun(dir, span.x, span.y, STEPS, jitter) +
                                closed_sun(dir, 0.0, span.x) + closed_sun(dir, span.y, t_end)
                              : closed_sun(dir, 0.0, t_end);
#elif METHOD == SHAFT_METHOD_ANALYTIC
    float a = closed_sun(dir, 0.0, t_end);
#else
    int layer = lights.lamp_count;
    float tn = texelFetch(u_sv_near, ivec3(px, layer), 0).r;
    float tf = texelFetch(u_sv_far, ivec3(px, layer), 0).r;
    float a = 0.0;
    if (tn >= 1.0e29) {
      float v0 = sun_visibility(camera.eye + dir * (0.5 * min(t_end, 10.0)));
      float v1 = sun_visibility(camera.eye + dir * (0.999 * t_march));
      if (v0 != v1) a = march_sun(dir, 0.0, t_march, STEPS, jitter);
      else if (v0 > 0.0) a = closed_sun(dir, 0.0, t_end);
    } else {
      if (sun_visibility(camera.eye + dir * (0.5 * tn)) > 0.0) a += closed_sun(dir, 0.0, tn);
      a += march_sun(dir, tn, tf, STEPS, jitter);
      float probe = tf + 0.5 * (min(t_end, tf + 10.0) - tf);
      if (sun_visibility(camera.eye + dir * probe) > 0.0) a += closed_sun(dir, tf, t_end);
    }
#endif
    L += lights.sun.power.rgb * a;
  }
  float alpha = (hit || sky || u_sigma_t > 0.0) ? 1.0 : 0.0;
  o_color = vec4(L, alpha);
}

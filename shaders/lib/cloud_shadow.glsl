// The clouds' shadow (cloud_shadow.hpp): transmittance towards the sun through every cloud,
// from the optical-depth map and the depth range of the cloud matter along each map texel.
// Compiled in only with CLOUD_SHADOW 1, so scenes without clouds pay nothing per sample.
#ifndef CLOUD_SHADOW
#define CLOUD_SHADOW 0
#endif
#if CLOUD_SHADOW
#include "lib/contract.glsl"
layout(binding = UNIT_CLOUD_TAU) uniform sampler2D u_cloud_tau;      // R32F, linear, border 0
layout(binding = UNIT_CLOUD_RANGE) uniform sampler2D u_cloud_range;  // RG32F, nearest: nearest and farthest depth with matter, metres
uniform mat4 u_world_to_cloud_map;  // world -> (x, y in [0, 1], depth along the light in metres)

float cloud_transmittance(vec3 p) {
  vec3 m = (u_world_to_cloud_map * vec4(p, 1.0)).xyz;
  float tau = textureLod(u_cloud_tau, m.xy, 0.0).r;
  vec2 range = textureLod(u_cloud_range, m.xy, 0.0).rg;
  // Before the matter: no shadow; beyond it: all of tau; inside: tau grows linearly with depth.
  float f = clamp((m.z - range.x) / max(range.y - range.x, 1.0e-3), 0.0, 1.0);
  return exp(-tau * f);
}

// The clouds' shadow on a surface, with the penumbra of the sun's disc (angular radius
// u_sun_angular_radius): the mean transmittance over the disc's footprint on the map, whose
// radius is the distance from the occluding matter to p times tan(radius), as in
// percentage-closer soft shadows (Fernando 2005) with transmittance in place of a depth test:
// 1. the occluder's depth: the optical-depth-weighted mean of the middle of the matter's depth
//    range, over CLOUD_PENUMBRA_TAPS taps within the widest footprint any matter could give
//    (its depth from the map's plane is at least 0);
// 2. the mean over CLOUD_PENUMBRA_TAPS taps spread evenly over the disc's footprint (a Vogel
//    spiral, equal areas) of the transmittance, itself interpolated bilinearly between texels
//    (textureGather), so a cloud's thin edge gives a partial shadow rather than a step in tau.
// The share of the matter before p (cloud_transmittance's f) is the centre's for every tap.
const int CLOUD_PENUMBRA_TAPS = 12;
uniform float u_sun_angular_radius;  // radians

vec2 cloud_penumbra_tap(int k, float radius_st) {
  float r = radius_st * sqrt((float(k) + 0.5) / float(CLOUD_PENUMBRA_TAPS));
  float a = 2.39996323 * float(k);  // the golden angle
  return r * vec2(cos(a), sin(a));
}

float cloud_transmittance_bilinear(vec2 st, float f) {
  vec2 res = vec2(textureSize(u_cloud_tau, 0));
  vec4 tau = textureGather(u_cloud_tau, st, 0);  // (i0, j1), (i1, j1), (i1, j0), (i0, j0); border 0
  vec4 t = exp(-tau * f);
  vec2 w = fract(st * res - 0.5);
  return mix(mix(t.w, t.z, w.x), mix(t.x, t.y, w.x), w.y);
}

float cloud_transmittance_soft(vec3 p) {
  vec3 m = (u_world_to_cloud_map * vec4(p, 1.0)).xyz;
  // Metres per unit of map x (the footprint's width; x and y take the same scale here only
  // when the footprint is square, so each axis is scaled by its own).
  vec2 per_st = vec2(1.0 / length(vec3(u_world_to_cloud_map[0][0], u_world_to_cloud_map[1][0], u_world_to_cloud_map[2][0])),
                     1.0 / length(vec3(u_world_to_cloud_map[0][1], u_world_to_cloud_map[1][1], u_world_to_cloud_map[2][1])));
  float tan_r = tan(u_sun_angular_radius);
  ivec2 res = textureSize(u_cloud_tau, 0);
  float weight = 0.0, depth = 0.0;
  for (int k = 0; k < CLOUD_PENUMBRA_TAPS; ++k) {
    vec2 st = m.xy + cloud_penumbra_tap(k, 1.0) * (max(m.z, 0.0) * tan_r) / per_st;
    ivec2 i = ivec2(floor(st * vec2(res)));
    if (any(lessThan(i, ivec2(0))) || any(greaterThanEqual(i, res))) continue;
    float tau = texelFetch(u_cloud_tau, i, 0).r;
    vec2 range = texelFetch(u_cloud_range, i, 0).rg;
    if (tau > 0.0 && range.y >= range.x) {
      weight += tau;
      depth += tau * 0.5 * (range.x + range.y);
    }
  }
  if (weight <= 0.0) return 1.0;  // no matter within reach of the sun's disc
  float occluder_m = max(m.z - depth / weight, 0.0);
  vec2 range = textureLod(u_cloud_range, m.xy, 0.0).rg;
  float f = range.y >= range.x ? clamp((m.z - range.x) / max(range.y - range.x, 1.0e-3), 0.0, 1.0) : 1.0;
  vec2 radius = vec2(occluder_m * tan_r) / per_st;
  float sum = 0.0;
  for (int k = 0; k < CLOUD_PENUMBRA_TAPS; ++k)
    sum += cloud_transmittance_bilinear(m.xy + cloud_penumbra_tap(k, 1.0) * radius, f);
  return sum / float(CLOUD_PENUMBRA_TAPS);
}
#else
float cloud_transmittance(vec3 p) { return 1.0; }
float cloud_transmittance_soft(vec3 p) { return 1.0; }
#endif

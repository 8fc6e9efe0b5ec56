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
#else
float cloud_transmittance(vec3 p) { return 1.0; }
#endif

// The lamp that lights the slicer's current pass (LAMP 1; light.hpp: a point light, or a
// spot): where the light comes from at a world point, and how much arrives there unshadowed,
// I w / max(r, r_min)^2 with the spot's weight w = smoothstep(cos outer, cos inner, cos angle).
#ifndef NIMBUS_CLOUD_LAMP_GLSL
#define NIMBUS_CLOUD_LAMP_GLSL

#include "lib/cloud_light_block.glsl"  // the lamp: slice_light.lamp_*
#include "lib/spot_cone.glsl"

// The light's propagation direction at x (unit, from the lamp to x).
vec3 lamp_propagation(vec3 x) {
  vec3 d = x - slice_light.lamp_position;
  return d * inversesqrt(max(dot(d, d), 1.0e-30));
}

// Unshadowed irradiance at x, given the propagation direction l there.
vec3 lamp_irradiance(vec3 x, vec3 l) {
  vec3 d = x - slice_light.lamp_position;
  float r2 = max(dot(d, d), slice_light.lamp_min_distance * slice_light.lamp_min_distance);
  float w = slice_light.lamp_spot.w > 0.5
                ? spot_cone_weight(dot(l, slice_light.lamp_spot.xyz), slice_light.lamp_cos.x, slice_light.lamp_cos.y)
                : 1.0;
  return slice_light.lamp_intensity * (w / r2);
}

#endif

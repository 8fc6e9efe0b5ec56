// The lamp that lights the slicer's current pass (LAMP 1; cloud_light.hpp: a point light, or a
// spot): where the light comes from at a world point, and how much arrives there unshadowed,
// I w / max(r, r_min)^2 with the spot's weight w = smoothstep(cos outer, cos inner, cos angle).
#ifndef NIMBUS_CLOUD_LAMP_GLSL
#define NIMBUS_CLOUD_LAMP_GLSL

uniform vec3 u_lamp_position;      // metres
uniform vec3 u_lamp_intensity;     // W/sr per channel
uniform vec4 u_lamp_spot;          // unit axis (propagation), w = 1 for a spot, 0 for a lamp
uniform vec2 u_lamp_cos;           // cos(outer), cos(inner) of the spot's cone
uniform float u_lamp_min_distance; // metres, > 0

// The light's propagation direction at x (unit, from the lamp to x).
vec3 lamp_propagation(vec3 x) {
  vec3 d = x - u_lamp_position;
  return d * inversesqrt(max(dot(d, d), 1.0e-30));
}

// Unshadowed irradiance at x, given the propagation direction l there.
vec3 lamp_irradiance(vec3 x, vec3 l) {
  vec3 d = x - u_lamp_position;
  float r2 = max(dot(d, d), u_lamp_min_distance * u_lamp_min_distance);
  float c = dot(l, u_lamp_spot.xyz);
  float span = u_lamp_cos.y - u_lamp_cos.x;
  float t = span > 0.0 ? clamp((c - u_lamp_cos.x) / span, 0.0, 1.0) : (c >= u_lamp_cos.y ? 1.0 : 0.0);
  float w = u_lamp_spot.w > 0.5 ? t * t * (3.0 - 2.0 * t) : 1.0;
  return u_lamp_intensity * (w / r2);
}

#endif

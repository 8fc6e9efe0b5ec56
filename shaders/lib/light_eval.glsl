// A light's unshadowed arrival at a point, the one evaluation the shaders and the CPU share:
// where the light propagates and the irradiance it delivers on a plane facing it (light.hpp's
// light_at, in float). The sun: parallel light of irradiance E. A lamp: I w / max(r, r_min)^2,
// with a spot's weight w = smoothstep(cos outer, cos inner, cos angle). Common subset of GLSL
// and C++: render/core/src/light_record.cpp compiles it, and tests/cpu/test_light_record.cpp
// checks it against light_at in double.
#ifndef NIMBUS_LIGHT_EVAL_GLSL
#define NIMBUS_LIGHT_EVAL_GLSL
#include "lib/light_record.glsl"
#include "lib/spot_cone.glsl"

bool light_is_sun(LightRecord L) { return L.position.w < 0.5f; }

// The unit direction the light propagates in at x: the sun's -to_sun everywhere, a lamp's from
// it to x.
vec3 light_propagation(LightRecord L, vec3 x) {
  if (light_is_sun(L)) return -vec3(L.position);
  vec3 d = x - vec3(L.position);
  return d * inversesqrt(max(dot(d, d), 1.0e-30f));
}

// A spot's weight for the unit propagation direction u (1 for the sun and for a lamp that is
// not a spot).
float light_spot_weight(LightRecord L, vec3 u) {
  return L.spot.w > 0.5f ? spot_cone_weight(dot(u, vec3(L.spot)), L.spot_cos.x, L.spot_cos.y) : 1.0f;
}

// The irradiance arriving at x on a plane facing the light, unshadowed, given the propagation
// direction l there (light_propagation).
vec3 light_irradiance(LightRecord L, vec3 x, vec3 l) {
  if (light_is_sun(L)) return vec3(L.power);
  vec3 d = x - vec3(L.position);
  float r2 = max(dot(d, d), L.power.w * L.power.w);
  return vec3(L.power) * (light_spot_weight(L, l) / r2);
}

#endif

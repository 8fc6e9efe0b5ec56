// The single-scattered airlight of lamp i of the LightsBlock over the segment [x0, x1] of the
// ray eye + x dir, per unit intensity, unshadowed: Sun et al.'s closed form for a lamp that
// shines every way (lib/airlight.glsl), the quadrature over its cone for a spot
// (lib/spot_airlight.glsl).
#ifndef NIMBUS_LAMP_AIRLIGHT_GLSL
#define NIMBUS_LAMP_AIRLIGHT_GLSL

#include "lib/light_list.glsl"
#include "lib/airlight.glsl"
#if SPOTS
#include "lib/spot_airlight.glsl"
#endif

float lamp_segment_airlight(int i, vec3 eye, vec3 dir, float x0, float x1, float sigma_t, float sigma_s,
                            int phase_kind, float phase_g) {
  vec3 to_light = lights.lamp[i].position.xyz - eye;
#if SPOTS
  if (lamp_is_spot(i))
    return spot_segment_airlight(sigma_t, sigma_s, to_light, dir, lights.lamp[i].spot.xyz, lights.lamp[i].spot_cos.x,
                                 lights.lamp[i].spot_cos.y, x0, x1, phase_kind, phase_g);
#endif
  float Dsv = max(length(to_light), 1.0e-20);
  float cg = clamp(dot(dir, to_light) / Dsv, -1.0, 1.0);
  float sg = min(length(cross(dir, to_light)) / Dsv, 1.0);
  return point_segment_airlight(sigma_t, sigma_s, 1.0, Dsv, cg, sg, x0, x1, phase_kind, phase_g);
}

#endif

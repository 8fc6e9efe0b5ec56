// The single-scattered airlight of a spot (light.hpp: a lamp narrowed to a cone) over a segment
// [x0, x1] of a view ray, per unit intensity, in float32:
//   A = int_x0^x1 sigma_s p(theta) w(u) e^(-sigma_t (x + d)) / d^2 dx
// (Sun et al. 2005 eq. 5 with the spot's weight w of its propagation direction u; theta the
// angle between u and the way back to the eye). Sun's closed form (lib/airlight.glsl) is for a
// lamp that shines every way; a cone leaves the integral to quadrature. With c the lamp's foot
// on the ray and h its distance from the ray's line, x = c + h tan(psi) turns dx / d^2 into
// dpsi / h and the inverse-square peak into a bounded integrand; along the ray
//   u = cos(psi) m + sin(psi) dir,   x + d = c + h (1 + sin psi) / cos psi,   cos(theta) = -sin(psi)
// (m the unit way from the lamp to the ray's line). u . axis = R cos(psi - phi) with
// R cos(phi) = m . axis, R sin(phi) = dir . axis, so the outer cone meets the ray where
// |psi - phi| <= acos(cos(outer) / R): one arc when the cone is at most a hemisphere wide, and
// the quadrature covers only its part of [psi0, psi1]. SPOT_AL_NODES midpoint nodes; measured
// against the double integral (render/media/spot_airlight.hpp) in tests/cpu/test_spot_airlight.cpp.
// Common subset of GLSL and C++: render/media/src/spot_airlight.cpp compiles this file too.
#ifndef NIMBUS_SPOT_AIRLIGHT_GLSL
#define NIMBUS_SPOT_AIRLIGHT_GLSL

#include "lib/phase.glsl"
#include "lib/spot_cone.glsl"

const int SPOT_AL_NODES = 32;
const float SPOT_AL_HALF_PI = 1.57079633f;
const float SPOT_AL_MAX_RESULT = 3.0e38f;  // results are clamped to stay finite

// to_lamp: the lamp's position minus the ray's origin (m); dir: the ray's unit direction; axis:
// the spot's unit axis (propagation); x0 < x1 metres along the ray (x1 >= 1e30: no end).
float spot_segment_airlight(float sigma_t, float sigma_s, vec3 to_lamp, vec3 dir, vec3 axis, float cos_outer,
                            float cos_inner, float x0, float x1, int phase_kind, float phase_g) {
  if (!(x1 > x0) || !(sigma_s > 0.0f)) return 0.0f;
  float c = dot(to_lamp, dir);
  vec3 off = to_lamp - c * dir;  // from the ray's line to the lamp
  float off_len = length(off);
  // On the ray's line any perpendicular will do, and h is floored so that 1 / h stays finite.
  vec3 side = abs(dir.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  vec3 m = off_len > 0.0f ? -off / off_len : normalize(cross(dir, side));
  float h = max(off_len, 1.0e-6f * max(length(to_lamp), 1.0f));
  float lo = atan((x0 - c) / h);
  float hi = atan((min(x1, 1.0e30f) - c) / h);

  float ma = dot(m, axis), da = dot(dir, axis);
  float R = sqrt(ma * ma + da * da);
  if (R <= cos_outer) return 0.0f;  // u . axis <= R: the ray never enters the cone
  if (R > 0.0f && cos_outer / R > -1.0f) {
    float delta = acos(cos_outer / R);
    if (delta <= SPOT_AL_HALF_PI) {  // at most a hemisphere: the arc [phi - delta, phi + delta]
      float phi = atan(da, ma);
      lo = max(lo, phi - delta);
      hi = min(hi, phi + delta);
      if (!(hi > lo)) return 0.0f;
    }
  }

  float dpsi = (hi - lo) / float(SPOT_AL_NODES);
  float sum = 0.0f;
  for (int k = 0; k < SPOT_AL_NODES; ++k) {
    float psi = lo + (float(k) + 0.5f) * dpsi;
    float s = sin(psi), co = cos(psi);
    float w = spot_cone_weight(co * ma + s * da, cos_outer, cos_inner);
    // (1 + sin) / cos without cancellation on either side of psi = 0.
    float q = s < 0.0f ? co / (1.0f - s) : (1.0f + s) / max(co, 1.0e-30f);
    float xd = c + min(h * q, 1.0e30f);
    sum += phase_value_pair(phase_kind, phase_g, 1.0f + s, 1.0f - s) * w * exp(-sigma_t * max(xd, 0.0f));
  }
  return min(sigma_s * sum * (dpsi / h), SPOT_AL_MAX_RESULT);
}

#endif

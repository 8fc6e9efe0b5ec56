// The clouds' dual-lobe Henyey-Greenstein phase (cloud_optics.hpp: DualLobePhase, as
// cloud_phase_value) and the octave sum of the Unreal-style multiple-scattering approximation
// (research-render.md section 2). Branch-free but for selects.
#ifndef NIMBUS_CLOUD_PHASE_GLSL
#define NIMBUS_CLOUD_PHASE_GLSL

const float CLOUD_INV_4PI = 0.0795774715;

// Henyey & Greenstein 1941, normalised per steradian; 1 + g^2 - 2 g cos is formed from the
// small one of 1 -+ cos so that the peaks keep their precision in float, and d^(-3/2) as
// inversesqrt(d)^3 (no division).
float cloud_hg(float g, float one_minus_cos, float one_plus_cos) {
  float d = g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * one_minus_cos
                     : (1.0 + g) * (1.0 + g) - 2.0 * g * one_plus_cos;
  float r = inversesqrt(max(d, 1.0e-12));
  return CLOUD_INV_4PI * (1.0 - g * g) * (r * r * r);
}

// p = w HG(g_forward) + (1 - w) HG(g_back); phase = (g_forward, g_back, w); theta = 0 forward.
float cloud_dual_phase(vec3 phase, float cos_theta) {
  float c = clamp(cos_theta, -1.0, 1.0);
  return phase.z * cloud_hg(phase.x, 1.0 - c, 1.0 + c) + (1.0 - phase.z) * cloud_hg(phase.y, 1.0 - c, 1.0 + c);
}

// sum_{k=0..octaves} b^k p(cos; c^k g) exp(-a^k tau), abc = (occlusion a, contribution b,
// eccentricity c); octaves = 0 is single scattering p exp(-tau). Pass a compile-time constant
// for `octaves` so that the loop unrolls.
float cloud_octaves(vec3 phase, vec3 abc, int octaves, float cos_theta, float tau) {
  float sum = 0.0;
  float a = 1.0;
  float b = 1.0;
  float c = 1.0;
  for (int k = 0; k <= octaves; ++k) {
    sum += b * cloud_dual_phase(vec3(phase.xy * c, phase.z), cos_theta) * exp(-a * tau);
    a *= abc.x;
    b *= abc.y;
    c *= abc.z;
  }
  return sum;
}

#endif

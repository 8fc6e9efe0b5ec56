// The clouds' dual-lobe Henyey-Greenstein phase (phase.hpp: a Phase in its dual-lobe form,
// as_dual_lobes, as phase_value) and the octave sum of the Unreal-style multiple-scattering approximation
// (after Wrenninge et al. 2013; cloud_optics.hpp: MultipleScattering). Branch-free but for
// selects.
#ifndef NIMBUS_CLOUD_PHASE_GLSL
#define NIMBUS_CLOUD_PHASE_GLSL

#include "lib/phase.glsl"

// p = w HG(g_forward) + (1 - w) HG(g_back); phase = (g_forward, g_back, w); theta = 0 forward.
float cloud_dual_phase(vec3 phase, float cos_theta) {
  float c = clamp(cos_theta, -1.0, 1.0);
  return phase.z * phase_hg(phase.x, 1.0 - c, 1.0 + c) + (1.0 - phase.z) * phase_hg(phase.y, 1.0 - c, 1.0 + c);
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

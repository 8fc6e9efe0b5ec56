// Phase functions (thesis eqs. 13-17), normalised over the sphere, theta = 0 forward: the one
// float implementation of each, for the fog (any kind, by its PHASE_* code of lib/contract.glsl)
// and for the clouds' dual-lobe Henyey-Greenstein (lib/cloud_phase.glsl). Written in the common
// subset of GLSL 4.50 and C++ (glm); render/media/src/airlight_stable.cpp compiles it.
#ifndef NIMBUS_PHASE_GLSL
#define NIMBUS_PHASE_GLSL

#include "lib/contract.glsl"
const float PHASE_INV_4PI = 0.0795774715f;
const float PHASE_SCHLICK_MAX_K = 0.999f;  // eq. 16 gives |k| > 1 for |g| > 0.938

// Schlick's k (thesis eq. 16), kept inside (-1, 1).
float phase_schlick_k(float g) {
  return clamp(1.55f * g - 0.55f * g * g * g, -PHASE_SCHLICK_MAX_K, PHASE_SCHLICK_MAX_K);
}

// Every phase function as p = scale (1 + rayleigh cos^2) / (d d^(1/2 or 1)) with
// d = d0 + d_minus (1 - cos) + d_plus (1 + cos): the coefficients depend on the kind and g only,
// so a shader forms them once and evaluates p without branches (on SIMD rasterisers such as
// llvmpipe every branch of a per-sample switch costs every sample).
struct PhaseCoeffs {
  float scale;     // normalisation
  float rayleigh;  // 1 for Rayleigh (eq. 17), else 0
  float d0, d_minus, d_plus;
  float schlick;   // 1: d^2 (Schlick, eq. 15); 0: d^(3/2) (Henyey-Greenstein, eq. 14)
};

PhaseCoeffs phase_coeffs(int kind, float g) {
  PhaseCoeffs pc;
  pc.scale = PHASE_INV_4PI;  // eq. 13
  pc.rayleigh = 0.0f;
  pc.d0 = 1.0f;
  pc.d_minus = 0.0f;
  pc.d_plus = 0.0f;
  pc.schlick = 0.0f;
  if (kind == PHASE_HENYEY_GREENSTEIN) {  // eq. 14: 1 + g^2 - 2 g cos = (1-g)^2 + 2g(1-cos) = (1+g)^2 - 2g(1+cos)
    pc.scale = PHASE_INV_4PI * (1.0f - g * g);
    pc.d0 = g >= 0.0f ? (1.0f - g) * (1.0f - g) : (1.0f + g) * (1.0f + g);
    pc.d_minus = g >= 0.0f ? 2.0f * g : 0.0f;
    pc.d_plus = g >= 0.0f ? 0.0f : -2.0f * g;
  } else if (kind == PHASE_SCHLICK) {  // eq. 15 with theta = 0 forward: 1 - k cos = (1-k) + k(1-cos) = (1+k) - k(1+cos)
    float k = phase_schlick_k(g);
    pc.scale = PHASE_INV_4PI * (1.0f - k * k);
    pc.d0 = k >= 0.0f ? 1.0f - k : 1.0f + k;
    pc.d_minus = k >= 0.0f ? k : 0.0f;
    pc.d_plus = k >= 0.0f ? 0.0f : -k;
    pc.schlick = 1.0f;
  } else if (kind == PHASE_RAYLEIGH) {  // eq. 17: 3/(16 pi) (1 + cos^2)
    pc.scale = 0.0596831037f;
    pc.rayleigh = 1.0f;
  }
  return pc;
}

// p(theta) from 1 - cos(theta) and 1 + cos(theta), each passed exactly so that the forward
// and backward peaks lose no precision in float (d is formed from the one that is small there).
float phase_value_coeffs(PhaseCoeffs pc, float one_minus_cos, float one_plus_cos) {
  float d = pc.d0 + pc.d_minus * one_minus_cos + pc.d_plus * one_plus_cos;
  float c = 0.5f * (one_plus_cos - one_minus_cos);
  return pc.scale * (1.0f + pc.rayleigh * c * c) / (d * mix(sqrt(d), d, pc.schlick));
}

// Henyey & Greenstein (thesis eq. 14): the one HG of the shaders, also the clouds' lobes.
float phase_hg(float g, float one_minus_cos, float one_plus_cos) {
  return phase_value_coeffs(phase_coeffs(PHASE_HENYEY_GREENSTEIN, g), one_minus_cos, one_plus_cos);
}

float phase_value_pair(int kind, float g, float one_minus_cos, float one_plus_cos) {
  return phase_value_coeffs(phase_coeffs(kind, g), one_minus_cos, one_plus_cos);
}

float phase_value(int kind, float g, float cos_theta) {
  float c = clamp(cos_theta, -1.0f, 1.0f);
  return phase_value_pair(kind, g, 1.0f - c, 1.0f + c);
}

#endif

// Phase functions (thesis eqs. 13-17), normalised over the sphere, theta = 0 forward. Written
// in the common subset of GLSL 4.50 and C++ (glm); render/src/airlight_stable.cpp compiles it.
#ifndef NIMBUS_PHASE_GLSL
#define NIMBUS_PHASE_GLSL

const int PHASE_ISOTROPIC = 0;
const int PHASE_HENYEY_GREENSTEIN = 1;
const int PHASE_SCHLICK = 2;
const int PHASE_RAYLEIGH = 3;
const float PHASE_INV_4PI = 0.0795774715f;
const float PHASE_SCHLICK_MAX_K = 0.999f;  // eq. 16 gives |k| > 1 for |g| > 0.938

// Schlick's k (thesis eq. 16), kept inside (-1, 1).
float phase_schlick_k(float g) {
  return clamp(1.55f * g - 0.55f * g * g * g, -PHASE_SCHLICK_MAX_K, PHASE_SCHLICK_MAX_K);
}

// p(theta) from 1 - cos(theta) and 1 + cos(theta), each passed exactly so that the forward
// and backward peaks lose no precision in float.
float phase_value_pair(int kind, float g, float one_minus_cos, float one_plus_cos) {
  if (kind == PHASE_HENYEY_GREENSTEIN) {  // eq. 14: 1 + g^2 - 2 g cos = (1-g)^2 + 2g(1-cos) = (1+g)^2 - 2g(1+cos)
    float d = g >= 0.0f ? (1.0f - g) * (1.0f - g) + 2.0f * g * one_minus_cos
                        : (1.0f + g) * (1.0f + g) - 2.0f * g * one_plus_cos;
    return PHASE_INV_4PI * (1.0f - g * g) / (d * sqrt(d));
  }
  if (kind == PHASE_SCHLICK) {  // eq. 15 with theta = 0 forward: (1 - k^2) / (4 pi (1 - k cos)^2)
    float k = phase_schlick_k(g);
    float d = k >= 0.0f ? (1.0f - k) + k * one_minus_cos : (1.0f + k) - k * one_plus_cos;
    return PHASE_INV_4PI * (1.0f - k * k) / (d * d);
  }
  if (kind == PHASE_RAYLEIGH) {  // eq. 17
    float c = 0.5f * (one_plus_cos - one_minus_cos);
    return 0.0596831037f * (1.0f + c * c);
  }
  return PHASE_INV_4PI;  // eq. 13
}

float phase_value(int kind, float g, float cos_theta) {
  float c = clamp(cos_theta, -1.0f, 1.0f);
  return phase_value_pair(kind, g, 1.0f - c, 1.0f + c);
}

#endif

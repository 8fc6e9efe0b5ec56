// Numerically stable single-scattering airlight of a point light (Sun et al. 2005, eq. 5) and
// of the sun, over any segment of a view ray (Biri et al. eqs. 10-12), in float32. Common
// subset of GLSL 4.50 and C++ (glm): render/src/airlight_stable.cpp compiles this file too.
// Derivation, panel layout and measured errors: docs/airlight.md.
#ifndef NIMBUS_AIRLIGHT_GLSL
#define NIMBUS_AIRLIGHT_GLSL

#include "lib/phase.glsl"

const float AL_INFINITY = 1.0e30f;    // x1 (or Dvp) >= this: the ray never ends
const float AL_MAX_RESULT = 3.0e38f;  // results are clamped to stay finite
const float AL_G_SPLIT = 2.0f;        // optical depth covered by the t panel (beyond the segment start)
const float AL_G_CUT = 16.0f;         // optical depth beyond which the rest (< e^-16) is dropped
const float AL_C = 32.0f;             // linear omega panel only where the exponent is < 1/AL_C
const float AL_RATIO = 4.0f;          // a panel [lo, hi] with hi > AL_RATIO lo uses a log variable
const float AL_FLOOR = 1.0e-6f;       // smallest omega, relative to the top of the omega side
const float AL_PEAK = 0.5f;           // forward peaks narrower than this in tan(theta/2) get panels

// 6-point Gauss-Legendre rule on [-1, 1] (positive half; the rule is symmetric).
const float AL_GL_X[3] = {0.2386191861f, 0.6612093865f, 0.9324695142f};
const float AL_GL_W[3] = {0.4679139346f, 0.3607615730f, 0.1713244924f};

// sin and cos on [0, pi/2] by their Taylor series (error < 6e-8): relative accuracy for small
// angles, whatever the GPU's sin does there.
float al_sin(float x) {
  float x2 = x * x;
  return x * (1.0f + x2 * (-1.6666667e-1f + x2 * (8.3333333e-3f + x2 * (-1.9841270e-4f +
             x2 * (2.7557319e-6f + x2 * -2.5052108e-8f)))));
}
float al_cos(float x) {
  float x2 = x * x;
  return 1.0f + x2 * (-0.5f + x2 * (4.1666667e-2f + x2 * (-1.3888889e-3f + x2 * (2.4801587e-5f +
         x2 * (-2.7557319e-7f + x2 * 2.0876757e-9f)))));
}

// atan(y / x) in [0, pi/2] for y, x >= 0 (not both 0), to a few 1e-8 relative: panel limits
// are differences of such angles, so the GPU's atan (often accurate only to an absolute 1e-7)
// is not used. Reduced to |z| <= tan(pi/8), then its Taylor series to z^17.
float al_atan_positive(float y, float x) {
  bool swapped = y > x;
  float r = swapped ? x / y : y / x;
  float base = 0.0f;
  if (r > 0.41421356f) {
    r = (r - 1.0f) / (r + 1.0f);
    base = 0.78539816f;
  }
  float z2 = r * r;
  float a = base + r * (1.0f + z2 * (-3.3333333e-1f + z2 * (2.0e-1f + z2 * (-1.4285714e-1f + z2 * (1.1111111e-1f +
                       z2 * (-9.0909091e-2f + z2 * (7.6923077e-2f + z2 * (-6.6666667e-2f + z2 * 5.8823529e-2f))))))));
  return swapped ? 1.57079633f - a : a;
}

float al_hypot(float a, float b) {
  float m = max(abs(a), abs(b));
  if (m == 0.0f) return 0.0f;
  float u = a / m;
  float v = b / m;
  return m * sqrt(u * u + v * v);
}

// d + along for a point at signed distance `along` past the light's foot point on the ray,
// h from the light's line, d = hypot(along, h): without cancellation ((d + along)(d - along) = h^2).
float al_plus(float along, float h, float d) {
  return along >= 0.0f ? d + along : h * (h / (d - along));
}

// Forward peak width of the phase function in tau = tan(theta/2); 1e30 when not peaked forward.
float al_forward_width(int kind, float g) {
  if (kind == PHASE_HENYEY_GREENSTEIN && g > 0.0f) return (1.0f - g) / (1.0f + g);
  if (kind == PHASE_SCHLICK) {
    float k = phase_schlick_k(g);
    if (k > 0.0f) return sqrt((1.0f - k) / (1.0f + k));
  }
  return 1.0e30f;
}

// Backward peak width in omega = (pi - theta)/2; 1e30 when not peaked backward.
float al_backward_width(int kind, float g) {
  if (kind == PHASE_HENYEY_GREENSTEIN && g < 0.0f) return (1.0f + g) / (2.0f * sqrt(-g));
  if (kind == PHASE_SCHLICK) {
    float k = phase_schlick_k(g);
    if (k < 0.0f) return sqrt((1.0f + k) / (-2.0f * k));
  }
  return 1.0e30f;
}

// The t side: t = (x + d(x) - d0) / r0 from the segment start, the integrand e^{-K t} p L(t)
// with L(t) = s / ((t + c)^2 + s^2) = d(omega)/dt; X = t + c is passed exactly.
float al_f_t(float t, float X, float K, float s, int kind, float g) {
  float q = X * X + s * s;
  return exp(-K * t) * (s / q) * phase_value_pair(kind, g, 2.0f * X * X / q, 2.0f * s * s / q);
}

float al_panel_t(float lo, float hi, float K, float s, float c, int kind, float g) {
  if (!(hi > lo)) return 0.0f;
  float half_len = 0.5f * (hi - lo);
  float mid = 0.5f * (hi + lo);
  float sum = 0.0f;
  for (int i = 0; i < 3; ++i) {
    float dt = half_len * AL_GL_X[i];
    sum += AL_GL_W[i] * (al_f_t(mid - dt, mid - dt + c, K, s, kind, g) +
                         al_f_t(mid + dt, mid + dt + c, K, s, kind, g));
  }
  return half_len * sum;
}

// Same integral with tau = (t + c)/s = tan(theta/2) on a log scale (the tail of a forward peak).
float al_panel_logtau(float lo, float hi, float K, float s, float c, int kind, float g) {
  if (!(hi > lo)) return 0.0f;
  float la = log((lo + c) / s);
  float lb = log((hi + c) / s);
  float half_len = 0.5f * (lb - la);
  float mid = 0.5f * (lb + la);
  float sum = 0.0f;
  for (int i = 0; i < 3; ++i) {
    for (int side = -1; side <= 1; side += 2) {
      float X = s * exp(mid + float(side) * half_len * AL_GL_X[i]);  // t + c
      sum += AL_GL_W[i] * X * al_f_t(max(X - c, 0.0f), X, K, s, kind, g);
    }
  }
  return half_len * sum;
}

// The omega side: omega = (pi - theta)/2 from 0 (x -> infinity) up; the exponent beyond the
// segment start is g = K (s cot(omega) - c).
float al_f_omega(float om, float K, float s, float c, int kind, float g) {
  float so = al_sin(om);
  float co = al_cos(om);
  float depth = K * (s * co / so - c);
  return exp(-depth) * phase_value_pair(kind, g, 2.0f * co * co, 2.0f * so * so);
}

float al_panel_omega(float lo, float hi, bool allow_log, float K, float s, float c, int kind, float g) {
  if (!(hi > lo)) return 0.0f;
  float sum = 0.0f;
  if (allow_log && AL_RATIO * lo < hi) {
    float la = log(lo);
    float lb = log(hi);
    float half_len = 0.5f * (lb - la);
    float mid = 0.5f * (lb + la);
    for (int i = 0; i < 3; ++i) {
      float om0 = exp(mid - half_len * AL_GL_X[i]);
      float om1 = exp(mid + half_len * AL_GL_X[i]);
      sum += AL_GL_W[i] * (om0 * al_f_omega(om0, K, s, c, kind, g) + om1 * al_f_omega(om1, K, s, c, kind, g));
    }
    return half_len * sum;
  }
  float half_len = 0.5f * (hi - lo);
  float mid = 0.5f * (hi + lo);
  for (int i = 0; i < 3; ++i) {
    float dw = half_len * AL_GL_X[i];
    sum += AL_GL_W[i] * (al_f_omega(mid - dw, K, s, c, kind, g) + al_f_omega(mid + dw, K, s, c, kind, g));
  }
  return half_len * sum;
}

// In-scattered radiance over the view-ray segment [x0, x1] (metres from the eye; x1 >= 1e30:
// infinite) from an isotropic point light of intensity I0 at distance Dsv, whose direction makes
// the angle gamma with the ray, for extinction sigma_t, scattering sigma_s and a phase function.
// Thesis eq. 33 over [x0, x1]; finite and >= 0 for all finite non-negative inputs.
float point_segment_airlight(float sigma_t, float sigma_s, float I0, float Dsv, float cos_gamma,
                             float sin_gamma, float x0, float x1, int phase_kind, float phase_g) {
  if (!(sigma_s > 0.0f) || !(I0 > 0.0f) || !(x1 > x0)) return 0.0f;
  bool infinite = x1 >= AL_INFINITY;
  // Lengths in units of D (the problem is scale-free but for sigma_t D).
  float D = max(Dsv, 1.0e-20f);
  float a = clamp(cos_gamma, -1.0f, 1.0f);  // foot point of the light on the ray
  float h = clamp(sin_gamma, 1.0e-7f, 1.0f);  // distance of the light from the ray's line
  float u0 = min(max(x0, 0.0f) / D, 1.0e18f);
  float along0 = u0 - a;
  float d0 = al_hypot(along0, h);
  float T = sigma_t * D;
  float base = T * (u0 + d0);  // optical depth light -> segment start -> eye
  if (!(base < 87.0f)) return 0.0f;
  float p0 = al_plus(along0, h, d0);
  float r0 = al_hypot(h, p0);  // sqrt(2 d0 p0)
  float s = h / r0;            // sin(psi0), psi0 = (pi - theta0)/2
  float c = p0 / r0;           // cos(psi0) = sin(theta0/2)
  float K = T * r0;            // exponent = K t beyond the segment start
  float tend = AL_INFINITY;
  if (!infinite) {
    float len = min((x1 - max(x0, 0.0f)) / D, 1.0e18f);
    float along1 = min(u0 + len, 1.0e18f) - a;
    float d1 = al_hypot(along1, h);
    float p1 = al_plus(along1, h, d1);
    tend = len * ((p0 + p1) / ((d0 + d1) * r0));
  }
  int kind = phase_kind;
  float g = phase_g;
  float sum = 0.0f;
  // t side: t in [0, min(tend, tsplit)], up to optical depth AL_G_SPLIT beyond the start.
  float tsplit = K > AL_G_SPLIT ? AL_G_SPLIT / K : 1.0f;
  float tE = min(tend, tsplit);
  float b = al_forward_width(kind, g);
  float tb = s * b - c;  // t where tan(theta/2) = b
  if (b < AL_PEAK && tb < tE) {
    float t1 = max(tb, 0.0f);
    sum += al_panel_t(0.0f, t1, K, s, c, kind, g);
    if (tE + c > AL_RATIO * (t1 + c)) sum += al_panel_logtau(t1, tE, K, s, c, kind, g);
    else sum += al_panel_t(t1, tE, K, s, c, kind, g);
  } else {
    sum += al_panel_t(0.0f, tE, K, s, c, kind, g);
  }
  // omega side: the rest of the segment, tan(omega) = s / (t + c).
  if (tend > tsplit) {
    float ob = al_atan_positive(s, tsplit + c);
    float oa = infinite ? 0.0f : al_atan_positive(s, tend + c);
    float o1 = 0.0f;  // where the exponent reaches 1
    if (K > 1.0e-30f) {
      o1 = al_atan_positive(s, 1.0f / K + c);
      oa = max(oa, al_atan_positive(s, AL_G_CUT / K + c));
    }
    oa = max(oa, AL_FLOOR * ob);
    float S = clamp(min(AL_C * o1, ob / AL_RATIO), oa, ob);
    float w = al_backward_width(kind, g);
    if (w < ob / AL_RATIO) {  // backward peak: log panels around its knee too
      float k1 = clamp(0.125f * w, oa, ob);
      float k2 = clamp(w, oa, ob);
      float q1 = min(S, k1);
      float q2 = max(k1, min(S, k2));
      float q3 = max(S, k2);
      sum += al_panel_omega(oa, q1, true, K, s, c, kind, g) + al_panel_omega(q1, q2, true, K, s, c, kind, g) +
             al_panel_omega(q2, q3, true, K, s, c, kind, g) + al_panel_omega(q3, ob, true, K, s, c, kind, g);
    } else {
      sum += al_panel_omega(oa, S, true, K, s, c, kind, g) + al_panel_omega(S, ob, false, K, s, c, kind, g);
    }
  }
  if (!(sum > 0.0f)) return 0.0f;
  // Eq. 33 in the angle variable: dx / d^2 = 2 d(omega) / (h D).
  float r = (sigma_s * exp(-base)) * ((2.0f / h) / D) * sum * I0;
  return r >= 0.0f ? min(r, AL_MAX_RESULT) : 0.0f;
}

// Sun et al. eq. 5 (isotropic, albedo 1): Sun's parameters; Dvp >= 1e30 is infinite.
float airlight_stable(float beta, float I0, float Dsv, float Dvp, float cos_gamma, float sin_gamma) {
  return point_segment_airlight(beta, beta, I0, Dsv, cos_gamma, sin_gamma, 0.0f, Dvp, PHASE_ISOTROPIC, 0.0f);
}

// Directional light of irradiance E, unattenuated toward the sun, over [x0, x1] (x1 >= 1e30:
// infinite): sigma_s p E (e^{-sigma_t x0} - e^{-sigma_t x1}) / sigma_t, stable as sigma_t -> 0.
float sun_segment_airlight(float sigma_t, float sigma_s, float E, float cos_theta, float x0, float x1,
                           int phase_kind, float phase_g) {
  if (!(sigma_s > 0.0f) || !(E > 0.0f) || !(x1 > x0)) return 0.0f;
  float t = max(sigma_t, 0.0f);
  float y0 = t * max(x0, 0.0f);
  if (!(y0 < 87.0f)) return 0.0f;
  float span;  // (1 - e^{-t L}) / t
  if (x1 >= AL_INFINITY) {
    span = t > 1.0e-30f ? 1.0f / t : AL_MAX_RESULT;
  } else {
    float len = x1 - max(x0, 0.0f);
    float y = t * len;
    span = y < 0.03f ? len * (1.0f - y * (0.5f - y * (1.6666667e-1f - y * (4.1666667e-2f - y * 8.3333333e-3f))))
                     : (1.0f - exp(-y)) / t;
  }
  float r = sigma_s * phase_value(phase_kind, phase_g, cos_theta) * E * exp(-y0) * span;
  return r >= 0.0f ? min(r, AL_MAX_RESULT) : 0.0f;
}

#endif

// Numerically stable single-scattering airlight of a point light (Sun et al. 2005, eq. 5) and
// of the sun, over any segment of a view ray (Biri et al. eqs. 10-12), in float32. Common
// subset of GLSL 4.50 and C++ (glm): render/media/src/airlight_stable.cpp compiles this file too.
// Written for SIMD rasterisers (llvmpipe runs 8 fragments in lock step and every branch costs
// every lane): a fixed panel layout with branch-free limits (peaked phase functions add nodes in
// one loop, skipped for the others), no trigonometric functions.
// Derivation, panel layout and measured errors: docs/airlight.md.
#ifndef NIMBUS_AIRLIGHT_GLSL
#define NIMBUS_AIRLIGHT_GLSL

#include "lib/phase.glsl"

const float AL_INFINITY = 1.0e30f;    // x1 (or Dvp) >= this: the ray never ends
const float AL_MAX_RESULT = 3.0e38f;  // results are clamped to stay finite
const float AL_G_SPLIT = 2.0f;        // optical depth covered by the T panel (beyond the segment start)
const float AL_G_CUT = 16.0f;         // optical depth beyond which the rest (< e^-16) is dropped
const float AL_G_U = 4.0f;            // the U panel covers at most this many more e-foldings ...
const float AL_C = 4.0f;              // ... and ends where the exponent reaches 1/AL_C ...
const float AL_RATIO = 4.0f;          // ... or X = t + c reaches AL_RATIO times its start, whichever is later
const float AL_FLOOR = 1.0e-6f;       // smallest u, relative to the top of the u side
const float AL_PEAK = 0.5f;           // forward peaks narrower than this in tan(theta/2) get panels

// 5-point Gauss-Legendre rule on [-1, 1].
const int AL_NODES = 5;
const float AL_NODE[5] = {-0.9061798459f, -0.5384693101f, 0.0f, 0.5384693101f, 0.9061798459f};
const float AL_WEIGHT[5] = {0.2369268851f, 0.4786286705f, 0.5688888889f, 0.4786286705f, 0.2369268851f};

// Panel variables; X = t + c = s tan(theta/2), u = s / X = tan(omega), omega = (pi - theta)/2.
const int AL_MAP_T = 0;    // v = t
const int AL_MAP_U = 1;    // v = sqrt(u)
const int AL_MAP_LOG = 2;  // v = ln(X / X(start))

// Forward peak width of the phase function in tau = tan(theta/2); 1e30 when not peaked forward.
float al_forward_width(int kind, float g) {
  if (kind == PHASE_HENYEY_GREENSTEIN && g > 0.0f) return (1.0f - g) / (1.0f + g);
  if (kind == PHASE_SCHLICK) {
    float k = phase_schlick_k(g);
    if (k > 0.0f) return sqrt((1.0f - k) / (1.0f + k));
  }
  return 1.0e30f;
}

// Backward peak width in u = tan(omega) (~ omega); 1e30 when not peaked backward.
float al_backward_width(int kind, float g) {
  if (kind == PHASE_HENYEY_GREENSTEIN && g < 0.0f) return (1.0f + g) / (2.0f * sqrt(-g));
  if (kind == PHASE_SCHLICK) {
    float k = phase_schlick_k(g);
    if (k < 0.0f) return sqrt((1.0f + k) / (-2.0f * k));
  }
  return 1.0e30f;
}

// ln(1 + r) for r >= 0, accurate for small r: 2 atanh(z), z = r / (2 + r), by its series for
// z < 1/3 (error < 2e-7 relative), else log.
float al_log1p(float r) {
  float z = r / (2.0f + r);
  float z2 = z * z;
  float series = 2.0f * z * (1.0f + z2 * (3.3333333e-1f + z2 * (2.0e-1f + z2 * (1.4285714e-1f + z2 * 1.1111111e-1f))));
  return z < 0.33333333f ? series : log(1.0f + r);
}

// The integrand e^{-K t} p(theta) s / ((t + c)^2 + s^2) times dt/dv, at the offset off = |v - v(ta)|
// from the start ta of a panel in the variable v of `map`. t is ta plus an offset formed without
// cancellation, and 1 -+ cos(theta) = 2 X^2 / q, 2 s^2 / q exactly.
float al_node(int map, float off, float ta, float K, float s, float c, PhaseCoeffs pc) {
  float Xa = ta + c;
  float va = map == AL_MAP_U ? sqrt(s / Xa) : 0.0f;
  float v = va - off;                             // map U: u = v^2 falls from s / Xa
  float e = map == AL_MAP_LOG ? exp(off) : 1.0f;  // map LOG: X = Xa e^off
  float X = map == AL_MAP_T ? Xa + off : (map == AL_MAP_U ? s / (v * v) : Xa * e);
  float t = ta + (map == AL_MAP_T ? off : (map == AL_MAP_U ? off * (va + v) * X * Xa / s : Xa * (e - 1.0f)));
  float q = X * X + s * s;
  float jac = map == AL_MAP_T ? s : (map == AL_MAP_U ? 2.0f * v * X * X : s * X);  // s dt/dv
  return exp(-K * t) * (jac / q) * phase_value_coeffs(pc, 2.0f * X * X / q, 2.0f * s * s / q);
}

// Length of the panel [ta, tb] in the variable of `map`, without cancellation.
float al_panel_length(int map, float ta, float tb, float s, float c) {
  float Xa = ta + c;
  float dt = tb - ta;
  float ua = s / Xa;
  float du = s * dt / (Xa * (tb + c));  // u(ta) - u(tb)
  return map == AL_MAP_T ? dt : (map == AL_MAP_U ? du / (sqrt(ua) + sqrt(ua - du)) : al_log1p(dt / Xa));
}

// int_ta^tb e^{-K t} p(theta) s / ((t + c)^2 + s^2) dt, Gauss-Legendre in the panel's variable.
float al_panel(int map, float ta, float tb, float K, float s, float c, PhaseCoeffs pc) {
  float half_len = 0.5f * al_panel_length(map, ta, tb, s, c);
  float sum = 0.0f;
  for (int i = 0; i < AL_NODES; ++i)
    sum += AL_WEIGHT[i] * al_node(map, half_len * (1.0f + AL_NODE[i]), ta, K, s, c, pc);
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
  float a = clamp(cos_gamma, -1.0f, 1.0f);    // foot point of the light on the ray
  float h = clamp(sin_gamma, 1.0e-7f, 1.0f);  // distance of the light from the ray's line
  float u0 = min(max(x0, 0.0f) / D, 1.0e18f);
  float along0 = u0 - a;
  float d0 = sqrt(along0 * along0 + h * h);
  float T = sigma_t * D;
  float base = T * (u0 + d0);  // optical depth light -> segment start -> eye
  if (!(base < 87.0f)) return 0.0f;
  float p0 = along0 >= 0.0f ? d0 + along0 : h * (h / (d0 - along0));  // d0 + along0 without cancellation
  float r0 = sqrt(h * h + p0 * p0);  // sqrt(2 d0 p0)
  float s = h / r0;                  // sin(psi0), psi0 = (pi - theta0)/2
  float c = p0 / r0;                 // cos(psi0) = sin(theta0/2)
  float K = max(T * r0, 1.0e-30f);   // exponent = K t beyond the segment start
  float tend = AL_INFINITY;
  if (!infinite) {
    float len = min((x1 - max(x0, 0.0f)) / D, 1.0e18f);
    float along1 = min(u0 + len, 1.0e18f) - a;
    float d1 = sqrt(along1 * along1 + h * h);
    float p1 = along1 >= 0.0f ? d1 + along1 : h * (h / (d1 - along1));
    tend = len * ((p0 + p1) / ((d0 + d1) * r0));
  }
  int kind = phase_kind;
  float g = phase_g;
  // Panels in t (docs/airlight.md), the same straight-line code for every input and phase:
  //   T [0, tb] up to tE: optical depth AL_G_SPLIT beyond the segment start, or t = 1;
  //   U [tU, tS]: the algebraic tail of the Lorentzian while the exponent is small;
  //   LOG [tS, ta]: the exponential cut-off, up to optical depth AL_G_CUT.
  // Peaked phase functions add LOG panels, one node per iteration of a loop whose trip count
  // depends on the phase function only (0 for isotropic, Rayleigh and mild peaks):
  //   forward, width b in tan(theta/2): [tb, tE] (tb where tan(theta/2) = b), halved in ln X;
  //   backward, width w in u: [tE, tw] halved in ln X (tw where u = w), then the knee [tw, t(w/8)],
  //   and the U panel starts at t(w/8).
  PhaseCoeffs pc = phase_coeffs(kind, g);
  float b = al_forward_width(kind, g);
  float w = al_backward_width(kind, g);
  float tE = min(tend, min(1.0f, AL_G_SPLIT / K));                           // end of the t side
  float ta = max(min(min(tend, AL_G_CUT / K), (tE + c) / AL_FLOOR - c), tE);  // end of the u side
  int n_extra = 0;  // extra LOG panels [e0, e1], [e1, e2], [e2, e3]
  float e0 = 0.0f;
  float e1 = 0.0f;
  float e2 = 0.0f;
  float e3 = 0.0f;
  float tb = tE;  // end of the T panel
  float tU = tE;  // start of the U panel
  if (b < AL_PEAK) {
    tb = clamp(s * b - c, 0.0f, tE);
    n_extra = 2;
    e0 = tb;
    e1 = clamp(sqrt((tb + c) * (tE + c)) - c, tb, tE);
    e2 = tE;
  } else if (w * (tE + c) < s) {
    float tw = clamp(s / w - c, tE, ta);  // u = w
    n_extra = 3;
    e0 = tE;
    e1 = clamp(sqrt((tE + c) * (tw + c)) - c, tE, tw);
    e2 = tw;
    e3 = clamp(8.0f * s / w - c, tw, ta);  // u = w / 8
    tU = e3;
  }
  float tS = clamp(min(max((1.0f / K + c) / AL_C - c, AL_RATIO * (tU + c) - c), tU + AL_G_U / K), tU, ta);
  float sum = al_panel(AL_MAP_T, 0.0f, tb, K, s, c, pc) + al_panel(AL_MAP_U, tU, tS, K, s, c, pc) +
              al_panel(AL_MAP_LOG, tS, ta, K, s, c, pc);
  float h0 = 0.5f * al_panel_length(AL_MAP_LOG, e0, e1, s, c);
  float h1 = 0.5f * al_panel_length(AL_MAP_LOG, e1, e2, s, c);
  float h2 = 0.5f * al_panel_length(AL_MAP_LOG, e2, e3, s, c);
  for (int j = 0; j < n_extra * AL_NODES; ++j) {
    int k = j / AL_NODES;
    int i = j - k * AL_NODES;
    float lo = k == 0 ? e0 : (k == 1 ? e1 : e2);
    float half_len = k == 0 ? h0 : (k == 1 ? h1 : h2);
    sum += half_len * AL_WEIGHT[i] * al_node(AL_MAP_LOG, half_len * (1.0f + AL_NODE[i]), lo, K, s, c, pc);
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

// The airlight of Sun et al. 2005: single-scattered radiance from an isotropic point light of
// intensity I0 (W/sr) along a view ray in a homogeneous medium, without occlusion. Four
// evaluations of the same model, so each approximation's error can be measured:
//   quadrature - double-precision adaptive quadrature of Sun eq. 5 (the reference);
//   table:N    - the classic factorisation A0 [F(A1, v1) - F(A1, gamma/2)] with an N x N
//                bilinear table of F(u, v) (Sun eqs. 7-12);
//   stable     - the float32 evaluation the shaders use (shaders/lib/airlight.glsl, compiled
//                here as C++ from the same source);
//   raymarch:N - N midpoint samples along the ray (the thesis' Algorithm 1 without occlusion).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "nimbus/render/core/phase.hpp"

namespace nimbus::render {

// One evaluation: Sun et al.'s parameters. beta is the extinction = scattering coefficient
// (albedo 1, per metre), I0 the light's intensity (W/sr), Dsv the light-viewer distance and
// Dvp the viewer-point distance (metres, may be +inf), gamma the angle between the view ray
// and the direction from the viewer to the light (radians, [0, pi]).
struct AirlightQuery {
  double beta = 0.0, I0 = 1.0, Dsv = 1.0, Dvp = 1.0, gamma = 1.0;
};

// Throws std::invalid_argument naming the field when a value is NaN, negative, or gamma is
// outside [0, pi]; Dvp may be +inf.
void validate(const AirlightQuery& q);

// Double-precision adaptive quadrature of Sun eq. 5 (relative tolerance ~1e-10).
double airlight_quadrature(const AirlightQuery& q);
// The float32 stable evaluation (same source as the shader).
double airlight_stable(const AirlightQuery& q);
// N midpoint samples over [0, min(Dvp, a finite cut-off beyond which the rest is < 1e-9)].
// With a phase function p, each sample is weighted by 4 pi p(theta) (isotropic: 1).
double airlight_raymarch(const AirlightQuery& q, int steps, const Phase& phase = {});
// The length airlight_raymarch marches: Dvp, or for Dvp = inf the cut-off beyond which the rest
// of the integral is below 1e-9 of the whole.
double airlight_raymarch_length(const AirlightQuery& q);

// Sun eq. 10: F(u, v) = integral_0^v exp(-u tan xi) dxi, tabulated on an N x N grid over
// u in [0, 10], v in [0, pi/2], read with bilinear interpolation (clamped outside).
class FTable {
 public:
  explicit FTable(int n);  // 16 <= n <= 1024, else std::invalid_argument
  int size() const { return n_; }
  double lookup(double u, double v) const;
  const float* data() const;  // n*n floats, row = v index, column = u index (for a GL texture)
 private:
  int n_;
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};
// Sun eq. 10 evaluated exactly (double adaptive quadrature).
double F_exact(double u, double v);
// Sun eqs. 7-12 with the table.
double airlight_table(const AirlightQuery& q, const FTable& table);

// General segment form used by renderers: in-scattered radiance over the view-ray segment
// [x0, x1] (metres from the eye, x1 may be +inf) from a point light at distance Dsv whose
// direction makes angle gamma with the ray, for extinction sigma_t, scattering sigma_s and
// any phase function. This is Biri et al.'s Gamma(x1) - Gamma(x0) (eqs. 10-12) computed as one
// integral, so it never subtracts nearly equal numbers.
struct SegmentQuery {
  double sigma_t = 0.0, sigma_s = 0.0, I0 = 1.0, Dsv = 1.0, cos_gamma = 1.0, sin_gamma = 0.0;
  double x0 = 0.0, x1 = 1.0;
  Phase phase;
};
// Sun's query as the segment [0, Dvp] from the eye (sigma_t = sigma_s = beta), with a phase.
SegmentQuery to_segment(const AirlightQuery& q, const Phase& phase = {});
double segment_airlight_quadrature(const SegmentQuery& q);  // double reference
double segment_airlight_stable(const SegmentQuery& q);      // float path (shader source)

// The shader's phase function (shaders/lib/phase.glsl) and its directional-light segment
// airlight sigma_s p E (e^{-sigma_t x0} - e^{-sigma_t x1}) / sigma_t, in float, for tests.
double phase_value_float(const Phase& phase, double cos_theta);
double sun_segment_airlight_stable(double sigma_t, double sigma_s, double E, double cos_theta, double x0,
                                   double x1, const Phase& phase);

// "quadrature", "stable", "table:N", "raymarch:N" -> evaluator; throws std::invalid_argument
// naming the text when malformed.
struct AirlightMethod {
  enum Kind { Quadrature, Stable, Table, RayMarch } kind = Stable;
  int n = 0;  // table size or steps
};
AirlightMethod parse_airlight_method(const std::string& text);
std::string to_string(const AirlightMethod& method);
// The method's AIRLIGHT_EVAL_* code in shaders/lib/contract.glsl (airlight_eval.comp.glsl);
// std::invalid_argument for Quadrature, which is CPU only.
int airlight_eval_code(AirlightMethod::Kind kind);

// Evaluates every query with one method on the CPU (validating each; the table is built once).
// A phase function other than isotropic replaces Sun's 1/(4 pi) (the segment form from the eye
// with sigma_t = sigma_s = beta); the table method is isotropic only (std::invalid_argument).
std::vector<double> evaluate_airlight(const std::vector<AirlightQuery>& queries, const AirlightMethod& method,
                                      const Phase& phase = {});
}  // namespace nimbus::render

// Airlight reflected by a Lambertian surface (Sun et al. 2005, section 4): the single-scattered
// light of an isotropic point light that reaches a surface point p from every direction of the
// hemisphere around its normal n, reflected by the BRDF. Sun eq. 13 splits the surface radiance
//   L_p = L_p,d + L_p,a,
// L_p,d (Sun eq. 14) being the direct term the renderers already shade, and
//   L_p,a = int_{hemisphere(n)} La(w) f_r cos(theta_w) dw,
// La(w) the airlight seen from p looking along w with no surface behind (Sun eq. 12, Tvp = inf).
// No occlusion: neither the lamp's shadows in the fog nor the surface's own geometry hide any of
// the hemisphere (Sun's model).
//
// The reduction (derivation in docs/shafts.md, "Airlight on surfaces"). La depends on w only
// through gamma, the angle between w and the direction from p to the light, and on the
// distance Dsp only through Tsp = sigma_t Dsp and a factor:
//   La(gamma) = (sigma_s I0 / Dsp) l(Tsp, gamma),
//   l(T, gamma) = 1/(4 pi) int_0^inf e^{-T (x + d(x))} / d(x)^2 dx,   d^2 = 1 + x^2 - 2 x cos(gamma)
// (Sun eq. 5 in units of Dsp; l = A0 [F(A1, pi/2) - F(A1, gamma/2)] / (sigma_s I0 / Dsp), Sun
// eqs. 7, 8, 12). With the light direction at angle theta_s from n, the azimuth phi around the
// light direction integrates in closed form:
//   W(gamma, theta_s) = int_0^2pi max(0, a + b cos phi) dphi,   a = cos g cos t_s, b = sin g sin t_s,
//                     = 2 pi max(a, 0)                 where b <= |a|,
//                     = 2 (a phi0 + sqrt(b^2 - a^2))   else, phi0 = acos(-a / b),
// (b^2 - a^2 = -cos(gamma + theta_s) cos(gamma - theta_s)), so that, for f_r = albedo / pi,
//   L_p,a = (albedo / pi) (sigma_s I0 / Dsp) G0(Tsp, theta_s),
//   G0(T, theta_s) = int_0^pi l(T, gamma) W(gamma, theta_s) sin(gamma) dgamma
// (Sun's G0, up to the constant factor he takes out). theta_s covers [0, pi]: a surface facing
// away from the light still receives airlight. G0 is bounded: G0(0, t_s) = lim T -> 0 is
// finite (l -> (pi - gamma) / (4 pi sin gamma)), and G0 ~ e^{-T} ln(T) / T for large T. The table
// stores g = G0 e^{T} (1 + T), which is O(1) and smooth in (ln T, theta_s).
//
// The medium's phase function: Sun's model is isotropic, but the reduction holds for any phase
// function p, because La still depends on w only through gamma (the scattering angle at each
// point of the ray from p is fixed by gamma and the distance along it): l then has
// sigma_s p(theta) in place of sigma_s / (4 pi). So nimbus tabulates G0 for the medium's own
// phase function (one table per phase, built on first use) rather than approximate it by the
// isotropic one, which for the scenes' hg:0.3 is off by -55 % to +55 % (docs/shafts.md).
#pragma once
#include <memory>
#include <vector>

#include "nimbus/render/core/phase.hpp"

namespace nimbus::render {

// One surface point lit by one point light. sigma_t (extinction) and sigma_s (scattering) per
// metre, I0 W/sr, Dsp the light-point distance (m), cos_theta_s the cosine of the angle between
// the surface normal and the direction from the point to the light ([-1, 1]), albedo the
// surface's Lambertian albedo ([0, 1]).
struct SurfaceAirlightQuery {
  double sigma_t = 0.0, sigma_s = 0.0, I0 = 1.0, Dsp = 1.0, cos_theta_s = 1.0, albedo = 1.0;
};
// Throws std::invalid_argument naming the field (NaN, negative, infinite, sigma_s > sigma_t,
// cos_theta_s outside [-1, 1], albedo outside [0, 1]).
void validate(const SurfaceAirlightQuery& q);

// The azimuthal integral W(gamma, theta_s) above (radians), exact.
double surface_airlight_W(double gamma, double theta_s);

// The dimensionless airlight l(T, gamma) from a point at unit distance (double, quadrature).
double surface_airlight_l(double T, double gamma, const Phase& phase = {});

// G0(T, theta_s) by nested adaptive Gauss-Kronrod (quadrature.hpp): outer over gamma in
// [0, pi] split at W's kinks (|pi/2 - theta_s|, min(pi/2 + theta_s, 3 pi/2 - theta_s)), at
// gamma = 4^-k (the l ~ 1/gamma peak toward the light, its gamma ln gamma term) and at
// T^(-1/2) 4^k (the width of that peak in thick media); inner l by
// segment_airlight_quadrature (relative 1e-11). Relative tolerance `rel_tol` (outer).
// With a phase function other than isotropic, sigma_s / (4 pi) becomes sigma_s p(theta).
double surface_airlight_G0_reference(double T, double theta_s, const Phase& phase = {}, double rel_tol = 1e-9);

// L_p,a of the query by the reference above (W sr^-1 m^-2), for the medium's phase function.
double surface_airlight_reference(const SurfaceAirlightQuery& q, const Phase& phase = {});

// G0 for one phase function tabulated as g = G0 e^{T} (1 + T) on an nx x ny grid: x = ln T uniform over
// [ln kTMin, ln kTMax], y = theta_s uniform over [0, pi] (ny odd, so that W's kinks fall on
// cell borders while building). Read bilinearly; T outside the range is clamped (T < kTMin:
// G0 changes by less than 2 T ln(1/T) below it, 1.8e-4 at theta_s = pi; T > kTMax: the float
// path's e^{-T} is 0).
// Built once per size and phase function in double (1.7 s on two cores here, docs/shafts.md), shared by
// all copies.
class SurfaceAirlightTable {
 public:
  static constexpr double kTMin = 1e-5, kTMax = 100.0;
  static constexpr int kDefaultNx = 128, kDefaultNy = 385;
  explicit SurfaceAirlightTable(const Phase& phase = {}, int nx = kDefaultNx, int ny = kDefaultNy);  // 8 <= nx <= 1024, 9 <= ny <= 2049 odd
  const Phase& phase() const { return phase_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  // g at grid node (i, j) in double, and the table as floats (row = theta_s index j, column =
  // ln T index i: a GL_R32F texture nx wide, ny high).
  double node(int i, int j) const;
  const float* data() const;
  // G0(T, theta_s) from the double table (bilinear in (ln T, theta_s)): what the CPU scene
  // reference uses.
  double G0(double T, double theta_s) const;

  struct Impl;

 private:
  Phase phase_;
  int nx_, ny_;
  std::shared_ptr<const Impl> impl_;
};

// L_p,a from the double table (the scene reference's term), for the table's phase function.
double surface_airlight_table(const SurfaceAirlightQuery& q, const SurfaceAirlightTable& table);
// L_p,a by the float path the surface shader runs (shaders/lib/surface_airlight.glsl compiled as
// C++, reading the table's floats).
double surface_airlight_float(const SurfaceAirlightQuery& q, const SurfaceAirlightTable& table);

}  // namespace nimbus::render

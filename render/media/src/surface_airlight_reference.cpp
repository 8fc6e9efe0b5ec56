// The double-precision reference of the airlight reflected by a Lambertian surface (Sun et al.
// section 4): G0(T, theta_s) = int_0^pi l(T, gamma) W(gamma, theta_s) sin(gamma) dgamma, the
// hemisphere integral with its azimuth done in closed form (surface_airlight.hpp), nested
// adaptive Gauss-Kronrod over gamma around segment_airlight_quadrature's l.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/core/quadrature.hpp"
#include "nimbus/render/media/surface_airlight.hpp"

namespace nimbus::render {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

void require(bool ok, const std::string& field, const std::string& rule, double v) {
  if (!ok) throw std::invalid_argument("surface airlight " + field + " must be " + rule + " (got " + std::to_string(v) + ")");
}

}  // namespace

void validate(const SurfaceAirlightQuery& q) {
  require(std::isfinite(q.sigma_t) && q.sigma_t >= 0.0, "sigma_t", "finite and >= 0", q.sigma_t);
  require(std::isfinite(q.sigma_s) && q.sigma_s >= 0.0 && q.sigma_s <= q.sigma_t, "sigma_s", "finite, >= 0 and <= sigma_t",
          q.sigma_s);
  require(std::isfinite(q.I0) && q.I0 >= 0.0, "I0", "finite and >= 0", q.I0);
  require(std::isfinite(q.Dsp) && q.Dsp > 0.0, "Dsp", "finite and > 0", q.Dsp);
  require(q.cos_theta_s >= -1.0 && q.cos_theta_s <= 1.0, "cos_theta_s", "in [-1, 1]", q.cos_theta_s);
  require(q.albedo >= 0.0 && q.albedo <= 1.0, "albedo", "in [0, 1]", q.albedo);
}

double surface_airlight_W(double gamma, double theta_s) {
  const double a = std::cos(gamma) * std::cos(theta_s);
  const double b = std::sin(gamma) * std::sin(theta_s);
  // b^2 - a^2 = -cos(gamma + theta_s) cos(gamma - theta_s), without cancellation.
  const double disc = -std::cos(gamma + theta_s) * std::cos(gamma - theta_s);
  if (!(disc > 0.0) || b <= std::abs(a)) return 2.0 * kPi * std::max(a, 0.0);
  const double phi0 = std::acos(std::clamp(-a / b, -1.0, 1.0));
  return 2.0 * (a * phi0 + std::sqrt(disc));
}

double surface_airlight_l(double T, double gamma, const Phase& phase) {
  SegmentQuery s;
  s.sigma_t = T;
  s.sigma_s = 1.0;
  s.I0 = 1.0;
  s.Dsv = 1.0;
  s.cos_gamma = std::cos(gamma);
  s.sin_gamma = std::sin(gamma);
  s.x0 = 0.0;
  s.x1 = kInf;
  s.phase = phase;
  return segment_airlight_quadrature(s);
}

double surface_airlight_G0_reference(double T, double theta_s, const Phase& phase, double rel_tol) {
  require(std::isfinite(T) && T >= 0.0, "T", "finite and >= 0", T);
  require(theta_s >= 0.0 && theta_s <= kPi, "theta_s", "in [0, pi]", theta_s);
  require(rel_tol > 0.0 && rel_tol <= 0.1, "rel_tol", "in (0, 0.1]", rel_tol);
  std::vector<double> cuts{std::abs(0.5 * kPi - theta_s), std::min(0.5 * kPi + theta_s, 1.5 * kPi - theta_s)};
  for (double g = 0.25; g > 1e-12; g *= 0.25) cuts.push_back(g);  // the 1/gamma peak toward the light
  if (T > 1.0)
    for (double k : {0.25, 1.0, 4.0}) cuts.push_back(k / std::sqrt(T));  // its width in thick media
  auto integrand = [&](double gamma) {
    const double w = surface_airlight_W(gamma, theta_s);
    return w > 0.0 ? surface_airlight_l(T, gamma, phase) * w * std::sin(gamma) : 0.0;
  };
  return integrate_adaptive(integrand, 0.0, kPi, cuts, rel_tol, 1e-300, 20000).value;
}

double surface_airlight_reference(const SurfaceAirlightQuery& q, const Phase& phase) {
  validate(q);
  if (q.sigma_s == 0.0 || q.I0 == 0.0 || q.albedo == 0.0) return 0.0;
  const double theta_s = std::acos(q.cos_theta_s);
  return q.albedo / kPi * (q.sigma_s * q.I0 / q.Dsp) * surface_airlight_G0_reference(q.sigma_t * q.Dsp, theta_s, phase);
}

}  // namespace nimbus::render

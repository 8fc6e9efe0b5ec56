// The double-precision references: adaptive quadrature of Sun et al. eq. 5 (thesis eq. 33)
// and of its general segment form, in the scattering-angle variable where the integrand is
// bounded and smooth (derivation in docs/airlight.md), plus Sun eq. 10's F(u, v).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "nimbus/render/core/quadrature.hpp"
#include "nimbus/render/media/airlight.hpp"

namespace nimbus::render {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRelTol = 1e-11;

void require(bool ok, const std::string& field, const std::string& rule, double v) {
  if (!ok) throw std::invalid_argument(field + " must be " + rule + " (got " + std::to_string(v) + ")");
}

void validate(const SegmentQuery& q) {
  require(std::isfinite(q.sigma_t) && q.sigma_t >= 0.0, "sigma_t", "finite and >= 0", q.sigma_t);
  require(std::isfinite(q.sigma_s) && q.sigma_s >= 0.0, "sigma_s", "finite and >= 0", q.sigma_s);
  require(std::isfinite(q.I0) && q.I0 >= 0.0, "I0", "finite and >= 0", q.I0);
  require(std::isfinite(q.Dsv) && q.Dsv >= 0.0, "Dsv", "finite and >= 0", q.Dsv);
  require(std::isfinite(q.cos_gamma), "cos_gamma", "finite", q.cos_gamma);
  require(std::isfinite(q.sin_gamma) && q.sin_gamma >= 0.0, "sin_gamma", "finite and >= 0", q.sin_gamma);
  require(std::abs(std::hypot(q.cos_gamma, q.sin_gamma) - 1.0) <= 1e-6, "cos_gamma^2 + sin_gamma^2", "1",
          std::hypot(q.cos_gamma, q.sin_gamma));
  require(std::isfinite(q.x0) && q.x0 >= 0.0, "x0", "finite and >= 0", q.x0);
  require(!std::isnan(q.x1) && q.x1 >= q.x0, "x1", ">= x0", q.x1);
  if (phase_takes_g(q.phase.kind)) require(q.phase.g > -1.0 && q.phase.g < 1.0, "phase g", "in (-1, 1)", q.phase.g);
  if (q.phase.kind == PhaseKind::DualHenyeyGreenstein) {
    require(q.phase.g_back > -1.0 && q.phase.g_back < 1.0, "phase g_back", "in (-1, 1)", q.phase.g_back);
    require(q.phase.forward_weight >= 0.0 && q.phase.forward_weight <= 1.0, "phase forward_weight", "in [0, 1]",
            q.phase.forward_weight);
  }
}

// The light lies on the ray's line (h = 0) at signed position a: closed forms or a bounded
// integral in y = 1/|x - a|; +inf when the light is on the segment.
double on_axis(const SegmentQuery& q, double a) {
  const double x0 = q.x0, x1 = q.x1;
  const double scale = q.sigma_s * q.I0;
  if (scale == 0.0) return 0.0;
  if (a >= x0 && a <= x1) return kInf;
  if (a > x1) {  // light ahead of the whole segment: forward scattering, x + d = a
    const double p = phase_value(q.phase, 1.0);
    return scale * p * std::exp(-q.sigma_t * a) * (x1 - x0) / ((a - x1) * (a - x0));
  }
  // Light behind the segment start: back scattering, d = x - a, x + d = 2x - a.
  const double p = phase_value(q.phase, -1.0);
  const double y0 = 1.0 / (x0 - a), y1 = std::isinf(x1) ? 0.0 : 1.0 / (x1 - a);
  const double t = q.sigma_t;
  auto f = [&](double y) { return y <= 0.0 ? (t > 0.0 ? 0.0 : 1.0) : std::exp(-2.0 * t * (1.0 / y - 1.0 / y0)); };
  const double integral = integrate_adaptive(f, y1, y0, {}, kRelTol).value;
  return scale * p * std::exp(-t * (2.0 * x0 - a)) * integral;
}

}  // namespace

void validate(const AirlightQuery& q) {
  require(std::isfinite(q.beta) && q.beta >= 0.0, "beta", "finite and >= 0", q.beta);
  require(std::isfinite(q.I0) && q.I0 >= 0.0, "I0", "finite and >= 0", q.I0);
  require(std::isfinite(q.Dsv) && q.Dsv >= 0.0, "Dsv", "finite and >= 0", q.Dsv);
  require(!std::isnan(q.Dvp) && q.Dvp >= 0.0, "Dvp", ">= 0 (inf allowed)", q.Dvp);
  require(q.gamma >= 0.0 && q.gamma <= kPi, "gamma", "in [0, pi]", q.gamma);
}

double segment_airlight_quadrature(const SegmentQuery& query) {
  validate(query);
  SegmentQuery q = query;
  const double norm = std::hypot(q.cos_gamma, q.sin_gamma);
  q.cos_gamma /= norm;
  q.sin_gamma /= norm;
  if (q.x1 == q.x0 || q.sigma_s == 0.0 || q.I0 == 0.0) return 0.0;
  const double a = q.Dsv * q.cos_gamma;  // along-ray position of the light's foot point
  const double h = q.Dsv * q.sin_gamma;  // distance of the light from the ray's line
  const double along0 = q.x0 - a;        // start of the segment relative to the foot point
  const double d0 = std::hypot(along0, h);
  if (h <= 1e-140 * std::max(d0, 1e-300)) return on_axis(q, a);
  const double base = q.sigma_t * (q.x0 + d0);  // optical depth light -> start -> eye
  if (base > 745.0) return 0.0;                 // exp underflows; the rest only decreases
  // Half-angle pair of the start: p0 = d0 + along0, m0 = d0 - along0, p0 m0 = h^2, each
  // formed where it does not cancel. psi0 = (pi - theta0)/2, tan psi0 = h / p0.
  double p0, m0;
  if (along0 >= 0.0) {
    p0 = d0 + along0;
    m0 = h * (h / p0);
  } else {
    m0 = d0 - along0;
    p0 = h * (h / m0);
  }
  const double psi0 = std::atan2(m0, h);
  double omega1 = 0.0;  // (pi - theta1)/2 at the segment end; 0 at infinity
  if (std::isfinite(q.x1)) {
    const double along1 = q.x1 - a;
    const double d1 = std::hypot(along1, h);
    omega1 = along1 >= 0.0 ? std::atan2(h, d1 + along1) : std::atan2(d1 - along1, h);
  }
  // g(omega) = sigma_t (x + d(x) - d0) = K sin(psi0 - omega) / sin(omega), K = 2 sigma_t d0 sin(theta0/2).
  const double K = q.sigma_t * std::sqrt(2.0 * d0 * p0);
  auto omega_at = [&](double g) { return std::atan2(K * std::sin(psi0), g + K * std::cos(psi0)); };
  double lo = omega1;
  if (K > 0.0) lo = std::max(lo, omega_at(800.0));  // beyond: exp(-g) == 0 in double
  if (!(psi0 > lo)) return 0.0;
  auto integrand = [&](double omega) {
    const double g = K > 0.0 ? K * std::sin(psi0 - omega) / std::sin(omega) : 0.0;
    const double cos_theta = -std::cos(2.0 * omega);  // theta = pi - 2 omega
    return phase_value(q.phase, cos_theta) * std::exp(-g);
  };
  std::vector<double> cuts;
  if (K > 0.0)
    for (double g : {0.25, 1.0, 4.0, 16.0, 64.0}) cuts.push_back(omega_at(g));
  if (phase_takes_g(q.phase.kind)) {
    double width = 1.0 - std::abs(q.phase.g);  // forward/back peak width in theta (the narrower lobe's)
    if (q.phase.kind == PhaseKind::DualHenyeyGreenstein) width = std::min(width, 1.0 - std::abs(q.phase.g_back));
    width = std::max(width, 1e-6);
    for (double k : {0.5, 2.0, 8.0}) {
      cuts.push_back(0.5 * (kPi - k * width));  // theta near 0
      cuts.push_back(0.5 * k * width);          // theta near pi
    }
  }
  const double integral = integrate_adaptive(integrand, lo, psi0, cuts, kRelTol).value;
  // Sun eq. 5 in the angle variable: dx / d^2 = 2 d(omega) / h.
  return q.sigma_s * q.I0 * (2.0 / h) * std::exp(-base) * integral;
}

SegmentQuery to_segment(const AirlightQuery& q, const Phase& phase) {
  SegmentQuery s;
  s.sigma_t = s.sigma_s = q.beta;
  s.I0 = q.I0;
  s.Dsv = q.Dsv;
  s.cos_gamma = std::cos(q.gamma);
  s.sin_gamma = std::sin(q.gamma);
  s.x0 = 0.0;
  s.x1 = q.Dvp;
  s.phase = phase;
  return s;
}

double airlight_quadrature(const AirlightQuery& q) {
  validate(q);
  return segment_airlight_quadrature(to_segment(q));
}

double F_exact(double u, double v) {
  if (!(u >= 0.0) || !std::isfinite(u)) throw std::invalid_argument("F(u, v): u must be finite and >= 0");
  if (!(v >= 0.0 && v <= 0.5 * kPi)) throw std::invalid_argument("F(u, v): v must be in [0, pi/2]");
  if (u == 0.0) return v;
  auto f = [u](double xi) {
    const double t = u * std::tan(xi);
    return t > 800.0 ? 0.0 : std::exp(-t);
  };
  std::vector<double> cuts;
  for (double t : {1.0, 8.0, 64.0}) cuts.push_back(std::atan(t / u));
  return integrate_adaptive(f, 0.0, v, cuts, kRelTol, 1e-300).value;
}

}  // namespace nimbus::render

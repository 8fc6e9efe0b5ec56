// The airlight by plain ray marching: N midpoint samples of Sun et al. eq. 5 in double (the
// thesis' Algorithm 1 without occlusion); an infinite ray is cut where the rest is negligible.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "nimbus/render/media/airlight.hpp"

namespace nimbus::render {

namespace {

// Where to stop an infinite ray. For x >= X >= a (a = Dsv cos gamma): d >= x - a, so the rest
// is at most beta I0 e^{-beta (2X - a)} / (4 pi (X - a)); the whole is at least its part over
// [0, Dsv], beta I0 e^{-3 Tsv} / (16 pi Dsv) (there d <= 2 Dsv and x + d <= 3 Dsv). X doubles
// from max(a, 0) + Dsv until the first is below 1e-9 of the second.
double cut_off(double beta, double Dsv, double gamma) {
  const double a = Dsv * std::cos(gamma);
  const double D = std::max(Dsv, 1.0 / beta * 1e-12);  // Dsv = 0 (a divergent integral): any finite scale
  const double budget = std::log(1e-9) - 3.0 * beta * D - std::log(4.0 * D);  // log of the allowed rest
  double X = std::max(a, 0.0) + D;
  for (int k = 0; k < 2100; ++k) {
    if (-beta * (2.0 * X - a) - std::log(X - a) <= budget) break;
    X *= 2.0;
  }
  return X;
}

}  // namespace

double airlight_raymarch_length(const AirlightQuery& q) {
  if (q.beta == 0.0) return 0.0;  // La = 0: nothing to march
  if (!std::isinf(q.Dvp)) return q.Dvp;
  return cut_off(q.beta, q.Dsv, q.gamma);
}

double airlight_raymarch(const AirlightQuery& q, int steps, const Phase& phase) {
  validate(q);
  if (steps < 1) throw std::invalid_argument("raymarch steps must be >= 1 (got " + std::to_string(steps) + ")");
  if (q.beta == 0.0 || q.I0 == 0.0 || q.Dvp == 0.0) return 0.0;
  const double length = airlight_raymarch_length(q);
  const double dx = length / steps;
  const double cg = std::cos(q.gamma);
  const bool isotropic = phase.kind == PhaseKind::Isotropic;
  double sum = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double x = (k + 0.5) * dx;
    const double d2 = q.Dsv * q.Dsv + x * x - 2.0 * x * q.Dsv * cg;  // cosine rule (Sun eq. 4)
    const double d = std::sqrt(d2);
    // cos(theta) = dot(unit(point - light), -view) = (Dsv cos(gamma) - x) / d
    const double weight = isotropic ? 1.0 : 4.0 * std::numbers::pi * phase_value(phase, (q.Dsv * cg - x) / d);
    sum += weight * std::exp(-q.beta * (x + d)) / d2;
  }
  return q.beta * q.I0 / (4.0 * std::numbers::pi) * sum * dx;  // Sun eq. 5 (thesis eq. 33)
}

}  // namespace nimbus::render

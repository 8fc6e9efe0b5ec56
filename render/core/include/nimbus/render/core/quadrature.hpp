// Adaptive Gauss-Kronrod quadrature (7-point Gauss, 15-point Kronrod) in double precision: the
// one integrator of every exact reference (the airlight evaluations and the shaft reference).
// Globally adaptive: it always splits the piece with the largest error estimate |K15 - G7|
// until the summed estimate meets the tolerance (Piessens et al. 1983, QUADPACK's qag scheme).
#pragma once
#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>
#include <vector>

namespace nimbus::render {

struct QuadratureResult {
  double value = 0.0;
  double error = 0.0;  // summed |K15 - G7| over the final pieces (a pessimistic bound)
  int pieces = 0;
  bool converged = true;  // false when max_pieces was reached first
};

namespace gk15 {
// Kronrod nodes on [-1, 1] (positive half, descending; the odd ones are the Gauss nodes) and
// weights (QUADPACK qk15's values).
inline constexpr double kNode[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
inline constexpr double kKronrod[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr double kGauss[4] = {  // for kNode[1], kNode[3], kNode[5], kNode[7]
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
}  // namespace gk15

// One G7-K15 evaluation on [a, b]: {K15 estimate, |K15 - G7|}.
template <class F>
std::pair<double, double> gauss_kronrod15(const F& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double kron = gk15::kKronrod[7] * fc, gauss = gk15::kGauss[3] * fc;
  for (int i = 0; i < 7; ++i) {
    const double dx = h * gk15::kNode[i];
    const double s = f(c - dx) + f(c + dx);
    kron += gk15::kKronrod[i] * s;
    if (i % 2 == 1) gauss += gk15::kGauss[i / 2] * s;
  }
  return {kron * h, std::abs((kron - gauss) * h)};
}

// Integral of f over the union of the given pieces [a, b] (a < b, finite), refined until the
// summed error estimate is <= rel_tol * |value| (or abs_tol), or max_pieces pieces exist.
template <class F>
QuadratureResult integrate_adaptive(const F& f, const std::vector<std::pair<double, double>>& pieces,
                                    double rel_tol, double abs_tol = 0.0, int max_pieces = 4000) {
  struct Piece {
    double a, b, value, error;
    bool operator<(const Piece& o) const { return error < o.error; }
  };
  std::priority_queue<Piece> queue;
  double value = 0.0, error = 0.0;
  for (const auto& [a, b] : pieces) {
    if (!(b > a)) continue;
    const auto [v, e] = gauss_kronrod15(f, a, b);
    queue.push({a, b, v, e});
    value += v;
    error += e;
  }
  QuadratureResult r;
  while (!queue.empty() && error > std::max(rel_tol * std::abs(value), abs_tol)) {
    if (static_cast<int>(queue.size()) >= max_pieces) {
      r.converged = false;
      break;
    }
    const Piece p = queue.top();
    const double m = 0.5 * (p.a + p.b);
    if (!(m > p.a && m < p.b)) {  // cannot split further in double
      r.converged = false;
      break;
    }
    queue.pop();
    const auto [v0, e0] = gauss_kronrod15(f, p.a, m);
    const auto [v1, e1] = gauss_kronrod15(f, m, p.b);
    queue.push({p.a, m, v0, e0});
    queue.push({m, p.b, v1, e1});
    value += v0 + v1 - p.value;
    error += e0 + e1 - p.error;
  }
  // Re-sum from the pieces so the running updates leave no rounding drift.
  r.pieces = static_cast<int>(queue.size());
  r.value = r.error = 0.0;
  while (!queue.empty()) {
    r.value += queue.top().value;
    r.error += queue.top().error;
    queue.pop();
  }
  return r;
}

// Integral of f over [a, b] (finite; nothing when b <= a), split first at the interior points
// among `breakpoints` (any order; others are ignored), then refined as above.
template <class F>
QuadratureResult integrate_adaptive(const F& f, double a, double b, std::vector<double> breakpoints, double rel_tol,
                                    double abs_tol = 0.0, int max_pieces = 2000) {
  std::vector<std::pair<double, double>> pieces;
  if (!(b > a)) return {};
  std::sort(breakpoints.begin(), breakpoints.end());
  double from = a;
  for (double p : breakpoints) {
    if (p > from && p < b) {
      pieces.emplace_back(from, p);
      from = p;
    }
  }
  pieces.emplace_back(from, b);
  return integrate_adaptive(f, pieces, rel_tol, abs_tol, max_pieces);
}

}  // namespace nimbus::render

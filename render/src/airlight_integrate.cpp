// Global adaptive Gauss-Kronrod 7/15 quadrature in double (the airlight reference integrator).
#include "airlight_detail.hpp"

#include <algorithm>
#include <cmath>
#include <queue>

namespace nimbus::render::detail {

namespace {

// Kronrod 15-point abscissae on [-1, 1] (positive half; odd indices are the 7 Gauss nodes)
// and weights, with the 7-point Gauss weights.
constexpr double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Piece {
  double a, b, value, error;
  bool operator<(const Piece& o) const { return error < o.error; }
};

Piece gk15(const std::function<double(double)>& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double k = kWgk[7] * fc, g = kWg[3] * fc;
  for (int i = 0; i < 7; ++i) {
    const double fs = f(c - h * kXgk[i]) + f(c + h * kXgk[i]);
    k += kWgk[i] * fs;
    if (i % 2 == 1) g += kWg[i / 2] * fs;
  }
  return {a, b, k * h, std::abs((k - g) * h)};
}

}  // namespace

QuadratureResult integrate_adaptive(const std::function<double(double)>& f, double a, double b,
                                    const std::vector<double>& breakpoints, double rel_tol, double abs_tol,
                                    int max_intervals) {
  QuadratureResult r;
  if (!(b > a)) return r;
  std::vector<double> cuts{a};
  std::vector<double> inner = breakpoints;
  std::sort(inner.begin(), inner.end());
  for (double p : inner)
    if (p > cuts.back() && p < b) cuts.push_back(p);
  cuts.push_back(b);
  std::priority_queue<Piece> heap;
  double value = 0.0, error = 0.0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const Piece p = gk15(f, cuts[i], cuts[i + 1]);
    value += p.value;
    error += p.error;
    heap.push(p);
  }
  int count = static_cast<int>(heap.size());
  while (error > std::max(rel_tol * std::abs(value), abs_tol) && count < max_intervals) {
    const Piece worst = heap.top();
    const double mid = 0.5 * (worst.a + worst.b);
    if (!(mid > worst.a && mid < worst.b)) break;  // interval at double resolution
    heap.pop();
    const Piece left = gk15(f, worst.a, mid), right = gk15(f, mid, worst.b);
    value += left.value + right.value - worst.value;
    error += left.error + right.error - worst.error;
    heap.push(left);
    heap.push(right);
    ++count;
  }
  // Re-sum from the pieces: the running sums above accumulate rounding.
  value = error = 0.0;
  r.intervals = static_cast<int>(heap.size());
  while (!heap.empty()) {
    value += heap.top().value;
    error += heap.top().error;
    heap.pop();
  }
  r.value = value;
  r.error = error;
  return r;
}

}  // namespace nimbus::render::detail

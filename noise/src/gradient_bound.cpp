// Numerical maximisation of the best-gradient sum over a lattice cell (see header).
#include "nimbus/noise/gradient_bound.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nimbus::noise {
namespace {

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

}  // namespace

double best_gradient_sum(int dims, const double* p) {
  double sum = 0.0;
  const int corners = 1 << dims;
  for (int c = 0; c < corners; ++c) {
    double w = 1.0;
    double d[4];
    for (int a = 0; a < dims; ++a) {
      const bool hi = (c >> a) & 1;
      d[a] = std::fabs(hi ? p[a] - 1.0 : p[a]);
      w *= hi ? fade(p[a]) : 1.0 - fade(p[a]);
    }
    // Best edge gradient: +-1 on the (dims - 1) largest |d| components, 0 on the smallest.
    for (int i = 1; i < dims; ++i)  // insertion sort, ascending
      for (int j = i; j > 0 && d[j] < d[j - 1]; --j) std::swap(d[j], d[j - 1]);
    double best = 0.0;
    for (int a = 1; a < dims; ++a) best += d[a];
    sum += w * best;
  }
  return sum;
}

BoundResult gradient_noise_bound(int dims) {
  if (dims != 3 && dims != 4) throw std::invalid_argument("gradient_noise_bound: dims must be 3 or 4");
  // Coarse grid over the cell, then a shrinking pattern search from the best few nodes.
  const int n = dims == 3 ? 48 : 24;
  BoundResult best{-1.0, {0, 0, 0, 0}};
  double p[4] = {0, 0, 0, 0};
  long total = 1;
  for (int a = 0; a < dims; ++a) total *= (n + 1);
  struct Cand { double v; double p[4]; };
  Cand top[8];
  int ntop = 0;
  for (long k = 0; k < total; ++k) {
    long r = k;
    for (int a = 0; a < dims; ++a) { p[a] = double(r % (n + 1)) / n; r /= (n + 1); }
    const double v = best_gradient_sum(dims, p);
    if (ntop < 8 || v > top[ntop - 1].v) {
      Cand c{v, {p[0], p[1], p[2], p[3]}};
      int i = std::min(ntop, 7);
      if (ntop < 8) ++ntop;
      top[i] = c;
      while (i > 0 && top[i].v > top[i - 1].v) { std::swap(top[i], top[i - 1]); --i; }
    }
  }
  for (int t = 0; t < ntop; ++t) {
    double q[4] = {top[t].p[0], top[t].p[1], top[t].p[2], top[t].p[3]};
    double v = top[t].v;
    for (double step = 1.0 / n; step > 1e-13; step *= 0.5) {
      bool improved = true;
      while (improved) {
        improved = false;
        for (int a = 0; a < dims; ++a) {
          for (int s = -1; s <= 1; s += 2) {
            double r[4] = {q[0], q[1], q[2], q[3]};
            r[a] = std::clamp(r[a] + s * step, 0.0, 1.0);
            const double rv = best_gradient_sum(dims, r);
            if (rv > v) { v = rv; std::copy(r, r + 4, q); improved = true; }
          }
        }
      }
    }
    if (v > best.bound) { best.bound = v; std::copy(q, q + 4, best.p); }
  }
  return best;
}

}  // namespace nimbus::noise

// Lit intervals of a view ray for the CPU reference: shadow regions of each occluder's bounds
// (exact for the box, so conservative for the occluder), dense shadow-ray samples inside them,
// bisection of every visibility change.
#include "nimbus/render/reference/reference_visibility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nimbus::render {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kBisectRel = 1e-9;  // visibility changes located to this relative precision

// A candidate: occluder k may shadow the ray only for x in [a, b].
struct Candidate {
  std::size_t k;
  double a, b;
};

// Lit intervals of [0, x_end] from sorted samples (first 0, last just below x_end): where two
// neighbours differ the change is bisected. The last sample's state extends to x_end (the end
// lies on a surface, where a shadow ray is ill-posed).
template <class Visible>
Intervals lit_from_samples(const Visible& visible, const std::vector<double>& xs, double x_end) {
  Intervals out;
  bool prev = visible(xs[0]);
  double start = 0.0;
  for (std::size_t i = 1; i < xs.size(); ++i) {
    const bool cur = visible(xs[i]);
    if (cur == prev) continue;
    double lo = xs[i - 1], hi = xs[i];
    while (hi - lo > kBisectRel * std::max(hi, 1.0)) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      (visible(mid) == prev ? lo : hi) = mid;
    }
    const double change = 0.5 * (lo + hi);
    if (prev) {
      out.emplace_back(start, change);
    } else {
      start = change;
    }
    prev = cur;
  }
  if (prev) out.emplace_back(start, x_end);
  return out;
}

double last_sample(double x_end) { return x_end - kBisectRel * std::max(x_end, 1.0); }

// Samples: 0, the last point, every candidate range's ends, and the grid points
// grid(i) (increasing in i) that fall inside a candidate range, found from index(x) = the
// grid's fractional index at x.
template <class Grid, class Index>
std::vector<double> samples_for(const std::vector<Candidate>& cands, double x_end, int n, const Grid& grid,
                                const Index& index) {
  const double last = std::max(last_sample(x_end), 0.0);
  std::vector<std::pair<double, double>> ranges;
  for (const Candidate& c : cands) ranges.emplace_back(c.a, c.b);
  std::sort(ranges.begin(), ranges.end());
  std::vector<double> xs{0.0, last};
  double covered = -kInf;  // grid points up to here are already in
  for (const auto& [a, b] : ranges) {
    xs.push_back(std::clamp(a, 0.0, last));
    xs.push_back(std::clamp(b, 0.0, last));
    const double from = std::max(a, covered);
    if (b <= from) continue;
    const int i0 = std::max(0, static_cast<int>(std::ceil(index(from))));
    const int i1 = std::min(n, static_cast<int>(std::floor(index(b))));
    for (int i = i0; i <= i1; ++i) xs.push_back(std::clamp(grid(i), 0.0, last));
    covered = b;
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  return xs;
}

// Pads a candidate range by a relative margin, so rounding in the clipping never cuts a
// true shadow short.
void pad(double& a, double& b) {
  a -= kBisectRel * std::max(std::abs(a), 1.0);
  b += kBisectRel * std::max(std::abs(b), 1.0);
}

}  // namespace

ShadowRegion point_shadow_region(const glm::dvec3& L, const glm::dvec3& lo, const glm::dvec3& hi) {
  ShadowRegion r;
  const double eps = 1e-9 * (1.0 + std::max({glm::length(lo), glm::length(hi), glm::length(L)}));
  if (glm::all(glm::greaterThan(L, lo - eps)) && glm::all(glm::lessThan(L, hi + eps))) {
    r.everywhere = true;
    return r;
  }
  glm::dvec3 c[8];
  for (int b = 0; b < 8; ++b) c[b] = {(b & 1) ? hi.x : lo.x, (b & 2) ? hi.y : lo.y, (b & 4) ? hi.z : lo.z};
  // The box side of the faces that face the light.
  for (int i = 0; i < 3; ++i) {
    glm::dvec3 n{0.0};
    if (L[i] < lo[i]) {
      n[i] = -1.0;
      r.planes[r.count++] = glm::dvec4(n, lo[i]);
    } else if (L[i] > hi[i]) {
      n[i] = 1.0;
      r.planes[r.count++] = glm::dvec4(n, -hi[i]);
    }
  }
  // The cone: planes through L and a box edge with all eight corners on one side.
  double scale = 0.0;
  for (const glm::dvec3& p : c) scale = std::max(scale, glm::length(p - L));
  for (int a = 0; a < 8; ++a) {
    for (const int bit : {1, 2, 4}) {
      if (a & bit) continue;
      glm::dvec3 n = glm::cross(c[a] - L, c[a | bit] - L);
      const double len = glm::length(n);
      if (!(len > 0.0)) continue;
      n /= len;
      double smin = kInf, smax = -kInf;
      for (const glm::dvec3& p : c) {
        const double s = glm::dot(n, p - L);
        smin = std::min(smin, s);
        smax = std::max(smax, s);
      }
      const double tol = 1e-12 * scale;
      if (smin >= -tol) n = -n;
      else if (smax > tol) continue;  // corners on both sides: not a silhouette edge
      r.planes[r.count++] = glm::dvec4(n, -glm::dot(n, L));
    }
  }
  return r;
}

bool clip_to_region(const ShadowRegion& r, const glm::dvec3& o, const glm::dvec3& d, double& x0, double& x1) {
  if (!r.everywhere) {
    for (int i = 0; i < r.count; ++i) {
      const glm::dvec3 n(r.planes[i]);
      const double a = glm::dot(n, o) + r.planes[i].w, b = glm::dot(n, d);  // a + b x <= 0
      if (b > 0.0) {
        x1 = std::min(x1, -a / b);
      } else if (b < 0.0) {
        x0 = std::max(x0, -a / b);
      } else if (a > 0.0) {
        return false;
      }
    }
  }
  return x0 <= x1;
}

bool sun_shadow_range(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& u, const glm::dvec3& lo,
                      const glm::dvec3& hi, double& xa, double& xb) {
  // Rows a x + b s <= c over (x, s >= 0) from lo_i <= o_i + d_i x + u_i s <= hi_i.
  struct Row {
    double a, b, c;
  };
  Row rows[7] = {{0.0, -1.0, 0.0}};
  for (int i = 0; i < 3; ++i) {
    rows[1 + 2 * i] = {d[i], u[i], hi[i] - o[i]};
    rows[2 + 2 * i] = {-d[i], -u[i], o[i] - lo[i]};
  }
  xa = -kInf;
  xb = kInf;
  auto on_x = [&](double a, double c) {  // a x <= c
    if (a > 0.0) {
      xb = std::min(xb, c / a);
    } else if (a < 0.0) {
      xa = std::max(xa, c / a);
    } else if (c < 0.0) {
      xa = kInf;  // infeasible
    }
  };
  // s >= alpha + beta x (lower) or s <= alpha + beta x (upper); every lower <= every upper.
  std::pair<double, double> lower[7], upper[7];
  int nl = 0, nu = 0;
  for (const Row& r : rows) {
    if (r.b > 0.0) {
      upper[nu++] = {r.c / r.b, -r.a / r.b};
    } else if (r.b < 0.0) {
      lower[nl++] = {r.c / r.b, -r.a / r.b};
    } else {
      on_x(r.a, r.c);
    }
  }
  for (int i = 0; i < nl; ++i) {
    for (int j = 0; j < nu; ++j) on_x(lower[i].second - upper[j].second, upper[j].first - lower[i].first);
  }
  return xa <= xb;
}

Intervals point_light_lit_intervals(const SceneTracer& tracer, const std::vector<ShadowRegion>& regions,
                                    const glm::dvec3& L, const glm::dvec3& o, const glm::dvec3& d, double x_end,
                                    int n) {
  const Scene& s = tracer.scene();
  // Every point of the ray before its end is on the eye's side of the ground plane: a light on
  // the other side (or on it) is hidden from all of them.
  if (s.ground && (L.y - s.ground->height_m) * (o.y - s.ground->height_m) <= 0.0) return {};
  std::vector<Candidate> cands;
  for (std::size_t k = 0; k < regions.size(); ++k) {
    double a = 0.0, b = x_end;
    if (clip_to_region(regions[k], o, d, a, b)) {
      pad(a, b);
      cands.push_back({k, a, b});
    }
  }
  if (cands.empty()) return {{0.0, x_end}};
  const auto visible = [&](double x) {
    const glm::dvec3 p = o + x * d;
    for (const Candidate& c : cands) {
      if (x >= c.a && x <= c.b && tracer.occluder_hit(c.k, p, L - p, 1.0)) return false;
    }
    return true;
  };
  // Grid 1: n + 1 points evenly in the angle seen from the light, x = xc + h tan(phi).
  const glm::dvec3 v = L - o;
  const double xc = glm::dot(v, d), h = glm::length(glm::cross(v, d));
  const double phi0 = std::atan2(-xc, h), phi1 = std::atan2(x_end - xc, h), dphi = (phi1 - phi0) / n;
  std::vector<double> xs;
  if (dphi > 0.0) {
    xs = samples_for(cands, x_end, n, [&](int i) { return xc + h * std::tan(phi0 + i * dphi); },
                     [&](double x) { return (std::atan2(x - xc, h) - phi0) / dphi; });
  }
  // Grid 2: n / 4 + 1 points evenly in x (covers h -> 0).
  const int m = std::max(n / 4, 1);
  const double dx = x_end / m;
  const std::vector<double> ys =
      samples_for(cands, x_end, m, [&](int i) { return i * dx; }, [&](double x) { return x / dx; });
  xs.insert(xs.end(), ys.begin(), ys.end());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  return lit_from_samples(visible, xs, x_end);
}

Intervals sun_lit_intervals(const SceneTracer& tracer, const glm::dvec3& u, const glm::dvec3& o,
                            const glm::dvec3& d, double x_end, int n) {
  const Scene& s = tracer.scene();
  // Seen from the eye's side of the ground plane, a sun on the other side is hidden.
  if (s.ground && (o.y - s.ground->height_m) * u.y < 0.0) return {};
  std::vector<Candidate> cands;
  double lo_all = kInf, hi_all = -kInf;
  for (std::size_t k = 0; k < tracer.occluder_count(); ++k) {
    glm::dvec3 lo, hi;
    tracer.occluder_bounds(k, lo, hi);
    double a, b;
    if (!sun_shadow_range(o, d, u, lo, hi, a, b)) continue;
    a = std::max(a, 0.0);
    b = std::min(b, x_end);
    if (a > b) continue;
    pad(a, b);
    cands.push_back({k, a, b});
    lo_all = std::min(lo_all, a);
    hi_all = std::max(hi_all, b);
  }
  if (cands.empty()) return {{0.0, x_end}};
  const auto visible = [&](double x) {
    const glm::dvec3 p = o + x * d;
    for (const Candidate& c : cands) {
      if (x >= c.a && x <= c.b && tracer.occluder_hit(c.k, p, u, kInf)) return false;
    }
    return true;
  };
  // n + 1 points evenly over the extent of the candidate ranges.
  const double dx = (hi_all - lo_all) / n;
  std::vector<double> xs;
  if (dx > 0.0) {
    xs = samples_for(cands, x_end, n, [&](int i) { return lo_all + i * dx; },
                     [&](double x) { return (x - lo_all) / dx; });
  } else {
    xs = samples_for(cands, x_end, 0, [&](int) { return lo_all; }, [&](double) { return 0.0; });
  }
  return lit_from_samples(visible, xs, x_end);
}

}  // namespace nimbus::render

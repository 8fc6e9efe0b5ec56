// The light volume's diffused high orders (light_volume_diffusion.hpp).
#include "nimbus/render/reference/light_volume_diffusion.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/base/cancel.hpp"

namespace nimbus::render::light_volume {

CellMedium cell_medium(const LightVolume& grid, const CellGrid& g, const std::vector<CloudVolume>& clouds) {
  CellMedium m;
  m.sigma_t.assign(g.cells(), 0.0);
  m.sigma_s.assign(g.cells(), glm::dvec3(0.0));
  m.mean_cosine.assign(g.cells(), 0.0);
  std::vector<glm::dvec3> shift;
  std::vector<double> cosine;
  for (const CloudVolume& c : clouds) {
    shift.emplace_back(c.box.origin[0], c.box.origin[1], c.box.origin[2]);
    cosine.push_back(phase_legendre(c.optics.phase, 1));
  }
  tbb::parallel_for(0, g.nz, [&](int k) {
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        double sigma_t = 0.0, g_sum = 0.0;
        glm::dvec3 sigma_s(0.0);
        for (int s = 0; s < 8; ++s) {
          const glm::dvec3 f(0.25 + 0.5 * (s & 1), 0.25 + 0.5 * ((s >> 1) & 1), 0.25 + 0.5 * (s >> 2));
          const glm::dvec3 world = grid.world_min + grid.cell_m * (glm::dvec3(i, j, k) + f);
          for (std::size_t c = 0; c < clouds.size(); ++c) {
            const glm::dvec3 local = glm::dvec3(clouds[c].world_to_index * glm::dvec4(world, 1.0)) - shift[c];
            const double st = clouds[c].optics.extinction_per_m * sample_density_local(clouds[c], local);
            if (!(st > 0.0)) continue;
            sigma_t += st;
            sigma_s += st * clouds[c].optics.albedo;
            g_sum += st * (clouds[c].optics.albedo.x + clouds[c].optics.albedo.y + clouds[c].optics.albedo.z) / 3.0 *
                     cosine[c];
          }
        }
        const std::size_t q = g.index(i, j, k);
        m.sigma_t[q] = sigma_t / 8.0;
        m.sigma_s[q] = sigma_s / 8.0;
        const double s_mean = (sigma_s.x + sigma_s.y + sigma_s.z) / 3.0;
        m.mean_cosine[q] = s_mean > 0.0 ? g_sum / s_mean : 0.0;
      }
  });
  return m;
}

std::vector<char> cells_deeper_than(const CellGrid& g, const glm::dvec3& cell_m, const CellMedium& medium, double depth) {
  // Dijkstra over the cells: a step between neighbours costs half of each one's optical
  // thickness across that axis; from a cell to vacuum (or past the grid) half its own.
  const std::size_t n = g.cells();
  auto sigma_tr = [&](std::size_t c) {
    const double s = (medium.sigma_s[c].x + medium.sigma_s[c].y + medium.sigma_s[c].z) / 3.0;
    return std::max(0.0, medium.sigma_t[c] - s * medium.mean_cosine[c]);
  };
  std::vector<double> tau(n, std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  for (std::size_t c = 0; c < n; ++c) {
    if (!(medium.sigma_t[c] > 0.0)) {
      tau[c] = 0.0;
      continue;
    }
    double edge = std::numeric_limits<double>::infinity();
    for (int f = 0; f < 6; ++f) {
      std::size_t r = 0;
      if (!g.face_neighbour(c, f, r) || !(medium.sigma_t[r] > 0.0)) edge = std::min(edge, 0.5 * sigma_tr(c) * cell_m[f / 2]);
    }
    if (edge < tau[c]) {
      tau[c] = edge;
      open.push({edge, c});
    }
  }
  while (!open.empty()) {
    const auto [t, c] = open.top();
    open.pop();
    if (t > tau[c]) continue;
    for (int f = 0; f < 6; ++f) {
      std::size_t r = 0;
      if (!g.face_neighbour(c, f, r) || !(medium.sigma_t[r] > 0.0)) continue;
      const double next = t + 0.5 * (sigma_tr(c) + sigma_tr(r)) * cell_m[f / 2];
      if (next < tau[r]) {
        tau[r] = next;
        open.push({next, r});
      }
    }
  }
  std::vector<char> deep(n, 0);
  for (std::size_t c = 0; c < n; ++c) deep[c] = medium.sigma_t[c] > 0.0 && tau[c] >= depth;
  return deep;
}

namespace {

constexpr std::size_t kChunk = 4096;  // fixed blocks for the dot products: the same sums whatever the threads

// One channel's linear system A phi = b over the cells with medium (the unknowns), in the
// finite-volume form of eq. MS-5 per unit volume: row i is
//   (sigma_a,i + sum_faces c_f) phi_i - sum_{faces to cells j} c_f phi_j = q_i,
// c_f = k_f / h_axis, k_f the face's conductance: 1 / (h / 2D_i + h / 2D_j) between cells,
// 1 / (h / 2D_i + 2) to vacuum (Marshak: J = phi_face / 2).
struct System {
  std::vector<std::size_t> cell;         // unknown -> cell
  std::vector<std::int32_t> neighbour;   // 6 per unknown: the unknown across each face, or -1 (vacuum)
  std::vector<double> coupling;          // 6 per unknown: c_f
  std::vector<double> diagonal;
  std::vector<double> conductance;       // 6 per unknown: k_f (for the currents)
  std::vector<double> diffusion;         // D per unknown
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size(), chunks = (n + kChunk - 1) / kChunk;
  std::vector<double> part(chunks, 0.0);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    double s = 0.0;
    for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) s += a[i] * b[i];
    part[c] = s;
  });
  double s = 0.0;
  for (double p : part) s += p;
  return s;
}

void multiply(const System& A, const std::vector<double>& x, std::vector<double>& y) {
  tbb::parallel_for(std::size_t{0}, x.size(), [&](std::size_t u) {
    double s = A.diagonal[u] * x[u];
    for (int f = 0; f < 6; ++f) {
      const std::int32_t v = A.neighbour[6 * u + f];
      if (v >= 0) s -= A.coupling[6 * u + f] * x[static_cast<std::size_t>(v)];
    }
    y[u] = s;
  });
}

System build_system(const CellGrid& g, const glm::dvec3& h, const CellMedium& medium, int channel,
                    const std::vector<std::int32_t>& unknown_of) {
  System A;
  for (std::size_t q = 0; q < g.cells(); ++q)
    if (unknown_of[q] >= 0) A.cell.push_back(q);
  const std::size_t n = A.cell.size();
  A.neighbour.assign(6 * n, -1);
  A.coupling.assign(6 * n, 0.0);
  A.conductance.assign(6 * n, 0.0);
  A.diagonal.assign(n, 0.0);
  A.diffusion.assign(n, 0.0);
  const double h_max = std::max({h.x, h.y, h.z});
  auto D_of = [&](std::size_t q) {
    const double sigma_tr = medium.sigma_t[q] - medium.sigma_s[q][channel] * medium.mean_cosine[q];
    // At most 100 cells' widths: a thinner cell (barely touched by cloud) is as good as
    // transparent, and the bound keeps the system's condition number finite.
    return 1.0 / (3.0 * std::max(sigma_tr, 1.0 / (300.0 * h_max)));
  };
  for (std::size_t u = 0; u < n; ++u) A.diffusion[u] = D_of(A.cell[u]);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t u) {
    const std::size_t q = A.cell[u];
    const double Di = A.diffusion[u];
    double diag = std::max(0.0, medium.sigma_t[q] - medium.sigma_s[q][channel]);  // sigma_a
    for (int f = 0; f < 6; ++f) {
      std::size_t r = 0;
      const std::int32_t v = g.face_neighbour(q, f, r) ? unknown_of[r] : -1;
      const double ha = h[f / 2];
      const double k_f = v >= 0 ? 1.0 / (ha / (2.0 * Di) + ha / (2.0 * A.diffusion[static_cast<std::size_t>(v)]))
                                : 1.0 / (ha / (2.0 * Di) + 2.0);
      A.neighbour[6 * u + f] = v;
      A.conductance[6 * u + f] = k_f;
      A.coupling[6 * u + f] = k_f / ha;
      diag += k_f / ha;
    }
    A.diagonal[u] = diag;
  });
  return A;
}

// Jacobi-preconditioned conjugate gradients (A is symmetric positive definite: every component
// of cells meets vacuum somewhere).
int conjugate_gradients(const System& A, const std::vector<double>& b, std::vector<double>& x, double tolerance,
                        int max_iterations, double& residual, const std::stop_token& stop) {
  const std::size_t n = b.size();
  x.assign(n, 0.0);
  std::vector<double> r = b, z(n), p(n), Ap(n);
  const double b_norm = std::sqrt(dot(b, b));
  residual = 0.0;
  if (!(b_norm > 0.0)) return 0;
  for (std::size_t u = 0; u < n; ++u) z[u] = r[u] / A.diagonal[u];
  p = z;
  double rz = dot(r, z);
  int it = 0;
  for (; it < max_iterations; ++it) {
    throw_if_stopped(stop);  // an iteration at a time (cancel.hpp)
    multiply(A, p, Ap);
    const double pAp = dot(p, Ap);
    if (!(pAp > 0.0) || !std::isfinite(pAp)) break;  // converged to rounding (A is positive definite)
    const double alpha = rz / pAp;
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t u) {
      x[u] += alpha * p[u];
      r[u] -= alpha * Ap[u];
      z[u] = r[u] / A.diagonal[u];
    });
    residual = std::sqrt(dot(r, r)) / b_norm;
    if (residual < tolerance) return it + 1;
    const double rz_next = dot(r, z);
    const double beta = rz_next / rz;
    rz = rz_next;
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t u) { p[u] = z[u] + beta * p[u]; });
  }
  return it;
}

}  // namespace

DiffusedLight solve_diffusion(const CellGrid& g, const glm::dvec3& cell_m, const CellMedium& medium,
                              const std::vector<glm::dvec3>& q, double tolerance, int max_iterations,
                              const std::stop_token& stop) {
  DiffusedLight out;
  out.fluence.assign(g.cells(), glm::dvec3(0.0));
  for (auto& f : out.flux) f.assign(g.cells(), glm::dvec3(0.0));
  std::vector<std::int32_t> unknown_of(g.cells(), -1);
  std::int32_t n = 0;
  for (std::size_t c = 0; c < g.cells(); ++c)
    if (medium.sigma_t[c] > 0.0) unknown_of[c] = n++;
  if (n == 0) return out;
  out.gradient.assign(g.cells(), glm::dvec3(0.0));
  // A grey medium lit by a grey source has one solution for all three channels.
  bool grey = true;
  for (std::size_t c = 0; c < g.cells() && grey; ++c)
    grey = medium.sigma_s[c].x == medium.sigma_s[c].y && medium.sigma_s[c].y == medium.sigma_s[c].z &&
           q[c].x == q[c].y && q[c].y == q[c].z;
  for (int channel = 0; channel < (grey ? 1 : 3); ++channel) {
    const System A = build_system(g, cell_m, medium, channel, unknown_of);
    std::vector<double> b(A.cell.size()), x;
    for (std::size_t u = 0; u < A.cell.size(); ++u) b[u] = std::max(0.0, q[A.cell[u]][channel]);
    double residual = 0.0;
    out.iterations = std::max(out.iterations, conjugate_gradients(A, b, x, tolerance, max_iterations, residual, stop));
    out.residual = std::max(out.residual, residual);
    for (std::size_t u = 0; u < A.cell.size(); ++u) {
      const std::size_t c = A.cell[u];
      const double phi = std::max(0.0, x[u]);
      // The net flux: the mean of the current J = k (phi_i - phi_j) through the cell's two faces
      // on each axis, signed along the axis (to vacuum phi_j = 0 and k is Marshak's); the
      // fluence's gradient in cells the mean of its two one-sided differences (to vacuum, the
      // face's own fluence phi_face = 2 J, half a cell away).
      glm::dvec3 F(0.0), grad(0.0);
      for (int f = 0; f < 6; ++f) {
        const std::int32_t v = A.neighbour[6 * u + f];
        const double sign = (f & 1) ? 1.0 : -1.0;
        const double across = v >= 0 ? x[static_cast<std::size_t>(v)] : 0.0;
        const double outward = A.conductance[6 * u + f] * (x[u] - across);
        F[f / 2] += 0.5 * sign * outward;
        const double rise = v >= 0 ? across - x[u] : 2.0 * (2.0 * outward - x[u]);
        grad[f / 2] += 0.5 * sign * rise;
      }
      for (int ch = channel; ch < (grey ? 3 : channel + 1); ++ch) {
        out.fluence[c][ch] = phi;
        out.flux[ch][c] = F;
      }
      out.gradient[c] += grad / (grey ? 1.0 : 3.0);
    }
  }
  return out;
}

}  // namespace nimbus::render::light_volume

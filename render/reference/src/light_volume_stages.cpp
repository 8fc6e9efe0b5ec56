// The light volume's stages after the photons (light_volume_stages.hpp).
#include "nimbus/render/reference/light_volume_stages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nimbus::render::light_volume {

namespace {

double mean_fluence(const std::vector<float>& value, std::size_t q) {
  return (value[q * kTallies] + value[q * kTallies + 1] + value[q * kTallies + 2]) / 3.0;
}

}  // namespace

LaunchRect launch_rect(const LightVolume& grid, const glm::dvec3& direction_to_sun) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  LaunchRect r;
  r.l = -glm::normalize(direction_to_sun);  // propagation
  const glm::dvec3 a = std::abs(r.l.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  r.eu = glm::normalize(glm::cross(a, r.l));
  r.ev = glm::cross(r.l, r.eu);
  r.umin = kInf, r.umax = -kInf, r.vmin = kInf, r.vmax = -kInf, r.lmin = kInf;
  const glm::dvec3 lo = grid.world_min, hi = grid.world_max();
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    r.umin = std::min(r.umin, glm::dot(p, r.eu));
    r.umax = std::max(r.umax, glm::dot(p, r.eu));
    r.vmin = std::min(r.vmin, glm::dot(p, r.ev));
    r.vmax = std::max(r.vmax, glm::dot(p, r.ev));
    r.lmin = std::min(r.lmin, glm::dot(p, r.l));
  }
  return r;
}

CellValues cell_values(const CellGrid& g, const std::vector<std::int64_t>& tally,
                       const std::vector<double>& covered, double scale) {
  const std::size_t n_cells = g.cells();
  CellValues v;
  v.value.assign(n_cells * kTallies, 0.0f);
  v.known.assign(n_cells, 0);
  g.for_each_cell([&](int i, int j, int k, std::size_t q) {
    if (!(covered[q] > 0.0)) return;
    v.known[q] = 1;
    if (covered[q] >= kPoolBelow) {
      for (int c = 0; c < kTallies; ++c)
        v.value[q * kTallies + c] =
            static_cast<float>(scale * static_cast<double>(tally[q * kTallies + c]) / covered[q]);
      return;
    }
    // A cell the cloud barely touches would divide a few rare collisions by a small covered
    // fraction (a firefly): it pools its neighbourhood instead (measured: no specks).
    double area = 0.0, sum[kTallies] = {};
    g.for_neighbourhood(i, j, k, [&](std::size_t r) {
      area += covered[r];
      for (int c = 0; c < kTallies; ++c) sum[c] += static_cast<double>(tally[r * kTallies + c]);
    });
    for (int c = 0; c < kTallies; ++c) v.value[q * kTallies + c] = static_cast<float>(scale * sum[c] / area);
  });
  return v;
}

void clamp_spikes(const CellGrid& g, CellValues& v) {
  // A rare flight through a thin brick (small majorant m, weight w / m per collision) could leave
  // one cell far brighter than every neighbour: a white blob where the eye sees it (measured: one
  // at the base of a tower of the default sky at 2^19 photons, faint at 2^21; 3x left a glow, 2x
  // none). The majorant's floor bounds each collision's weight; this clamp is the guard against
  // what photon noise is left. Scattered light diffuses, so a cell may not stand far above its
  // neighbours.
  const std::vector<float> before = v.value;
  g.for_each_cell([&](int i, int j, int k, std::size_t q) {
    if (!v.known[q]) return;
    double sum = 0.0;
    int count = 0;
    g.for_neighbourhood(i, j, k, [&](std::size_t r) {
      if (r == q || !v.known[r]) return;
      sum += mean_fluence(before, r);
      ++count;
    });
    const double own = mean_fluence(before, q);
    if (count < 6 || !(own > kSpike * sum / count)) return;
    const double f = kSpike * (sum / count) / own;
    for (int c = 0; c < kTallies; ++c) v.value[q * kTallies + c] = static_cast<float>(before[q * kTallies + c] * f);
  });
}

void smooth_anisotropy(const CellGrid& g, CellValues& v) {
  // The flux and the second moment carry the view-dependent part, and their noise shows as white
  // specks where a cell's noisy flux happens to point at the eye (measured: one at seed 1 on
  // cumulus-mediocris, none at seed 2). They vary slowly in space; a fluence-weighted mean of the
  // neighbours' F / phi keeps |F| <= phi.
  const std::vector<float> before = v.value;
  g.for_each_cell([&](int i, int j, int k, std::size_t q) {
    if (!v.known[q]) return;
    double sum[kTallies] = {}, phi = 0.0;
    g.for_neighbourhood(i, j, k, [&](std::size_t r) {
      if (!v.known[r]) return;
      phi += mean_fluence(before, r);  // F, Q: the channels' mean
      for (int c = 3; c < kMomentTally; ++c) sum[c] += before[r * kTallies + c];
    });
    const double own = mean_fluence(before, q);
    for (int c = 3; c < kMomentTally; ++c)
      v.value[q * kTallies + c] = phi > 0.0 ? static_cast<float>(own * sum[c] / phi) : 0.0f;
  });
}

std::vector<float> linear_fits(const CellGrid& g, const CellValues& v, const Coverage& cov) {
  // With phi(u) = phi_bar + g . (u - ubar) over the covered part, the first moment about the
  // centre M = phi_bar ubar + diag(spread) g, so g = (M - phi_bar ubar) / spread per axis.
  std::vector<float> fit(g.cells() * 4, 0.0f);
  g.for_each_cell([&](int i, int j, int k, std::size_t q) {
    if (!(cov.covered[q] >= kPoolBelow)) return;
    const double phi = mean_fluence(v.value, q);
    if (!(phi > 0.0)) return;
    glm::dvec3 grad(0.0);
    for (int ax = 0; ax < 3; ++ax)
      if (cov.spread[q][ax] > 1e-3)
        grad[ax] = (v.value[q * kTallies + kMomentTally + ax] - phi * cov.centroid[q][ax]) / cov.spread[q][ax];
    const double reach = glm::dot(glm::abs(grad), 0.5 + glm::abs(cov.centroid[q]));
    if (reach > phi) grad *= phi / reach;
    const glm::dvec3 ubar = glm::dvec3(i, j, k) + 0.5 + cov.centroid[q];
    for (int ax = 0; ax < 3; ++ax) fit[4 * q + ax] = static_cast<float>(grad[ax]);
    fit[4 * q + 3] = static_cast<float>(glm::dot(grad, ubar));
  });
  return fit;
}

void fill_empty_rings(const CellGrid& g, CellValues& v, std::vector<float>& fit, int rings) {
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> next = v.known;
    g.for_each_cell([&](int i, int j, int k, std::size_t q) {
      if (v.known[q]) return;
      const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
      int count = 0;
      double sum[kTallies] = {}, fit_sum[4] = {};
      for (const auto& b : nb) {
        if (b[0] < 0 || b[0] >= g.nx || b[1] < 0 || b[1] >= g.ny || b[2] < 0 || b[2] >= g.nz) continue;
        const std::size_t r = g.index(b[0], b[1], b[2]);
        if (!v.known[r]) continue;
        ++count;
        for (int c = 0; c < kTallies; ++c) sum[c] += v.value[r * kTallies + c];
        for (int c = 0; c < 4; ++c) fit_sum[c] += fit[4 * r + c];
      }
      if (count == 0) return;
      // The mean of the neighbours' fits too (eq. MS-4 is linear in them): the lookups
      // between an edge cell and this one follow the edge cell's fit, not a constant.
      for (int c = 0; c < kTallies; ++c) v.value[q * kTallies + c] = static_cast<float>(sum[c] / count);
      for (int c = 0; c < 4; ++c) fit[4 * q + c] = static_cast<float>(fit_sum[c] / count);
      next[q] = 1;
    });
    v.known.swap(next);
  }
}

void pack_light_volume(const CellValues& v, std::vector<float>&& fit, bool fits, const glm::dvec3& l,
                       LightVolume& out) {
  const std::size_t n_cells = v.known.size();
  const std::vector<float>& value = v.value;
  out.fluence_rgb.resize(n_cells * 3);
  out.flux_xyz.resize(n_cells * 3);
  out.quadrupole.resize(n_cells * 5);
  out.lobes.assign(n_cells * 4, 0.0f);
  if (fits) out.gradient = std::move(fit);
  out.light_direction = l;
  for (std::size_t q = 0; q < n_cells; ++q) {
    for (int c = 0; c < 3; ++c) {
      out.fluence_rgb[3 * q + c] = value[q * kTallies + c];
      out.flux_xyz[3 * q + c] = value[q * kTallies + 3 + c];
    }
    for (int c = 0; c < 5; ++c) out.quadrupole[5 * q + c] = value[q * kTallies + 6 + c];
    // Eq. MS-3's lobes: f_k = phi_k / phi, mu_k = (phi_k mean cosine to the sun) / phi_k.
    const double phi = mean_fluence(value, q);
    double room = 1.0;
    for (int o = 0; o < 2; ++o) {
      const double phi_k = value[q * kTallies + kLobeTally + 2 * o], along = value[q * kTallies + kLobeTally + 2 * o + 1];
      if (!(phi > 0.0 && phi_k > 0.0)) continue;
      const double f = std::min(phi_k / phi, room);
      room -= f;
      out.lobes[4 * q + 2 * o] = static_cast<float>(f);
      out.lobes[4 * q + 2 * o + 1] = static_cast<float>(std::clamp(along / phi_k, -0.95, 0.95));
    }
  }
}

}  // namespace nimbus::render::light_volume

// The light volume's photon tracer (light_volume_builder.hpp).
#include "nimbus/render/reference/light_volume_builder.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "traced_media.hpp"

namespace nimbus::render {

using namespace traced;

namespace {

constexpr std::size_t kMaxBytes = std::size_t{2} << 30;  // 2 GiB
// Fluence RGB, flux xyz, Q xx yy xy xz yz; then per lobe order k = 1, 2: its fluence and its
// flux along the sun's direction (channels' means).
// Then the first moment of position about the cell's centre, in cells, xyz (eq. MS-4's fit).
constexpr int kTallies = 18;
constexpr int kLobeTally = 11;
constexpr int kMomentTally = 15;
constexpr int kSubsamples = 4;                           // per cell axis, for the covered fraction
constexpr double kMaxRefined = 128.0;                    // cells along the longest axis, at most, when refining

// The brick majorant of `m` at a world point (0 outside its bricks).
double majorant_at(const TracedCloud& m, const glm::dvec3& world) {
  const glm::dvec3 u = glm::dvec3(m.cloud->world_to_index * glm::dvec4(world, 1.0)) - m.shift + 1.0;
  int b[3];
  for (int a = 0; a < 3; ++a) {
    const double x = std::floor(u[a] / kBrick);
    if (!(x >= 0.0 && x < m.nb[a])) return 0.0;
    b[a] = static_cast<int>(x);
  }
  return m.majorant[static_cast<std::size_t>(b[0] + m.nb[0] * (b[1] + m.nb[1] * b[2]))];
}

double total_majorant(const std::vector<TracedCloud>& media, const glm::dvec3& world) {
  double s = 0.0;
  for (const TracedCloud& m : media) s += majorant_at(m, world);
  return s;
}


// Delta tracking in one cloud as TracedCloud::free_flight, recording every tentative collision
// (the real one included) into `points`. Returns the real collision's distance or +inf.
double free_flight_recorded(const TracedCloud& c, const glm::dvec3& o, const glm::dvec3& d, double t1, PathRng& rng,
                            std::vector<double>& points) {
  double hit = kInf;
  c.march(o, d, 0.0, t1, [&](double s0, double s1, double m, const glm::dvec3& lo, const glm::dvec3& ld) {
    if (m <= 0.0) return true;
    double t = s0;
    while (true) {
      t -= std::log(1.0 - rng.uniform()) / m;
      if (t >= s1) return true;
      points.push_back(t);
      if (rng.uniform() * m < c.sigma_t(lo, ld, t)) {
        hit = t;
        return false;
      }
    }
  });
  return hit;
}

}  // namespace

LightVolume light_volume_grid(const std::vector<CloudVolume>& clouds, const LightVolumeSettings& settings) {
  validate(settings);
  if (clouds.empty()) throw std::invalid_argument("light volume clouds: the list is empty");
  glm::dvec3 lo, hi;
  cloud_bounds(clouds, lo, hi);
  const glm::dvec3 extent = hi - lo;
  const double longest = std::max({extent.x, extent.y, extent.z});
  if (!(longest > 0.0) || !std::isfinite(longest))
    throw std::invalid_argument("light volume clouds: their bounds are empty or not finite");
  LightVolume v;
  // Cube cells, but at least kMinAcross across a thin axis: the eye sees the first mean free
  // path under a layer's base, and 3 cells across the 500 m stratus sheet left it 63 % too bright
  // from below, 8 cells (with eq. MS-4's fits) 5 % (docs/clouds.md).
  constexpr int kMinAcross = 8;
  double cube = longest / settings.resolution;
  // Finer where the photons allow. A cell's error is its photon noise (variance ~ 1 / the photons
  // through it) against its size (its mean smears the steep gradient of the light inside a sunlit
  // surface, which the eye sees the first mean free path of). The photons launched per unit area
  // set the first: cells of side c over the box's largest face A get about N c^2 / A photons each.
  // Measured (docs/clouds.md, bench look, 2^21 photons): 1000 a cell face keeps the 22 m cells of
  // cumulus-mediocris and the 208 m cells of the 10 km stratus sheet, where finer ones were worse
  // (photon noise), and refines the 64 m cells of the 3 km congestus tower to 50 m: they smeared
  // its sunlit limb (HG 0.7, front- and back-lit: 10.6 and 10.0 % -> 8.7 and 8.7 %). No finer
  // than the clouds' voxels (no detail below them) nor 128 cells along the longest axis (memory).
  if (settings.photons_per_cell > 0.0) {
    const double face = std::max({extent.x * extent.y, extent.y * extent.z, extent.x * extent.z});
    double voxel = kInf;
    for (const CloudVolume& c : clouds)
      for (int a = 0; a < 3; ++a) voxel = std::min(voxel, glm::length(glm::dvec3(c.index_to_world[a])));
    const double budget = std::sqrt(settings.photons_per_cell * face / static_cast<double>(settings.photons));
    cube = std::min(cube, std::max({budget, voxel, longest / kMaxRefined}));
  }
  v.world_min = lo;
  v.cell_m = glm::dvec3(cube);
  const int along = std::max(settings.resolution, static_cast<int>(std::ceil(longest / cube - 1e-9)));
  for (int a = 0; a < 3; ++a) {
    v.size[a] = std::clamp(static_cast<int>(std::ceil(extent[a] / cube - 1e-9)), 1, along);
    if (v.size[a] < kMinAcross) {
      v.size[a] = std::min(kMinAcross, along);
      v.cell_m[a] = extent[a] / v.size[a];
    }
  }
  v.photons = settings.photons;
  v.seed = settings.seed;
  v.lobe_orders = settings.lobe_orders;
  return v;
}

std::size_t light_volume_bytes(const LightVolume& grid) {
  // Tallies (int64), the covered fraction (double), the values and the result (float).
  return grid.cells() * (kTallies * sizeof(std::int64_t) + sizeof(double) + 2 * kTallies * sizeof(float) + 1);
}

LightVolume build_light_volume(const std::vector<CloudVolume>& clouds, const CloudLight& light,
                               const LightVolumeSettings& settings) {
  validate(light);
  if (light.kind != CloudLightKind::Sun)
    throw std::invalid_argument("light volume light: photons come from the sun only; a lamp takes the octaves method of multiple scattering");
  LightVolume v = light_volume_grid(clouds, settings);
  if (light_volume_bytes(v) > kMaxBytes)
    throw std::length_error("light volume: " + std::to_string(v.size[0]) + "x" + std::to_string(v.size[1]) + "x" +
                            std::to_string(v.size[2]) + " cells would take " + std::to_string(light_volume_bytes(v) >> 20) +
                            " MiB, more than 2048");
  std::vector<TracedCloud> media = media_of(clouds);
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n_cells = v.cells();
  const int nx = v.size[0], ny = v.size[1], nz = v.size[2];
  const glm::dvec3 cell = v.cell_m;
  const double shortest = std::min({cell.x, cell.y, cell.z}), widest = std::max({cell.x, cell.y, cell.z});
  // A tentative collision stands for 1 / m metres of track, so in a brick of thin cloud (small
  // majorant m) one flight's few collisions count kilometres: a cluster of cells that support
  // each other past the spike clamp (measured: 2x2 cells at 4x their surroundings on the congestus
  // tower's shadowed face, a white blob, 78 % of that case's squared error). Any m at least the
  // extinction is a majorant, so each brick's is raised to one collision per cell's width: a
  // collision then stands for at most a cell's width of track.
  for (TracedCloud& m : media)
    for (double& b : m.majorant)
      if (b > 0.0) b = std::max(b, 1.0 / shortest);
  // The launch rectangle: perpendicular to the light, covering the grid's box seen from the sun.
  const glm::dvec3 l = -glm::normalize(light.direction_to_light);  // propagation
  const glm::dvec3 a = std::abs(l.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 eu = glm::normalize(glm::cross(a, l)), ev = glm::cross(l, eu);
  double umin = kInf, umax = -kInf, vmin = kInf, vmax = -kInf, lmin = kInf;
  const glm::dvec3 hi = v.world_max();
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p((c & 1) ? hi.x : v.world_min.x, (c & 2) ? hi.y : v.world_min.y, (c & 4) ? hi.z : v.world_min.z);
    umin = std::min(umin, glm::dot(p, eu));
    umax = std::max(umax, glm::dot(p, eu));
    vmin = std::min(vmin, glm::dot(p, ev));
    vmax = std::max(vmax, glm::dot(p, ev));
    lmin = std::min(lmin, glm::dot(p, l));
  }
  const double area_m2 = (umax - umin) * (vmax - vmin);
  const std::int64_t n = settings.photons;
  // Positions on the rectangle: the R2 sequence (Roberts 2018), shifted per seed (Cranley-Patterson).
  PathRng shift_rng(settings.seed, ~std::uint64_t{0});
  const double shift_u = shift_rng.uniform(), shift_v = shift_rng.uniform();

  // Fixed-point tallies of weight x metres: integer sums do not depend on the order of the adds.
  const double quantum = 1e-9 * shortest;
  std::vector<std::atomic<std::int64_t>> tally(n_cells * kTallies);
  for (auto& t : tally) t.store(0, std::memory_order_relaxed);
  auto add = [&](std::size_t idx, double value) {
    tally[idx].fetch_add(std::llround(value / quantum), std::memory_order_relaxed);
  };

  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, n, 1024), [&](const tbb::blocked_range<std::int64_t>& r) {
      std::vector<double> points;
      for (std::int64_t i = r.begin(); i < r.end(); ++i) {
        PathRng rng(settings.seed, static_cast<std::uint64_t>(i));
        const double fi = static_cast<double>(i);
        const double x = std::fmod(shift_u + fi * 0.7548776662466927, 1.0);
        const double y = std::fmod(shift_v + fi * 0.5698402909980532, 1.0);
        glm::dvec3 o = eu * (umin + x * (umax - umin)) + ev * (vmin + y * (vmax - vmin)) + l * (lmin - widest);
        glm::dvec3 d = l;
        // The unscattered flight: single scattering is the slicer's own, so nothing is tallied.
        Collision c = collide(media, o, d, rng);
        if (c.medium < 0) continue;
        glm::dvec3 weight(1.0);
        for (int bounce = 1; bounce < 100000; ++bounce) {
          const CloudVolume& hit = *media[static_cast<std::size_t>(c.medium)].cloud;
          o += c.t * d;
          weight *= hit.optics.albedo;
          if (bounce >= 16 && !survives_roulette(weight, rng)) break;  // as the path tracer
          if (!(std::max({weight.x, weight.y, weight.z}) > 0.0)) break;
          d = sample_phase(hit.optics.phase, d, rng);
          // The next flight, every cloud's tentative collisions recorded; the nearest real one ends it.
          points.clear();
          c = Collision{};
          for (std::size_t j = 0; j < media.size(); ++j) {
            const double t = free_flight_recorded(media[j], o, d, c.t, rng, points);
            if (t < c.t) {
              c.t = t;
              c.medium = static_cast<int>(j);
            }
          }
          // Each tentative collision stands for 1 / (the majorants' sum there) metres of track.
          for (double t : points) {
            if (t > c.t) continue;
            const glm::dvec3 p = o + t * d;
            const glm::dvec3 u = (p - v.world_min) / cell;  // in cells
            const glm::dvec3 ijk = glm::floor(u);
            // The bricks reach up to 7 voxels past a cloud's support, where only null collisions
            // happen; the grid covers the support alone, and a point beyond it is no cell's track
            // (clamped into the edge cells it made the stratus sheet's top layer 5.5x too bright).
            if (!(ijk.x >= 0.0 && ijk.y >= 0.0 && ijk.z >= 0.0 && ijk.x < nx && ijk.y < ny && ijk.z < nz)) continue;
            const double m = total_majorant(media, p);
            if (!(m > 0.0)) continue;
            const std::size_t k =
                (static_cast<std::size_t>(ijk.x) + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(ijk.y) +
                                                                                  static_cast<std::size_t>(ny) * static_cast<std::size_t>(ijk.z))) *
                kTallies;
            const glm::dvec3 wt = weight / m;
            add(k + 0, wt.x);
            add(k + 1, wt.y);
            add(k + 2, wt.z);
            const double mean = (wt.x + wt.y + wt.z) / 3.0;
            add(k + 3, mean * d.x);
            add(k + 4, mean * d.y);
            add(k + 5, mean * d.z);
            // The traceless second moment: w (d d^T - I / 3).
            add(k + 6, mean * (d.x * d.x - 1.0 / 3.0));
            add(k + 7, mean * (d.y * d.y - 1.0 / 3.0));
            add(k + 8, mean * d.x * d.y);
            add(k + 9, mean * d.x * d.z);
            add(k + 10, mean * d.y * d.z);
            const glm::dvec3 off = u - ijk - 0.5;
            add(k + kMomentTally + 0, mean * off.x);
            add(k + kMomentTally + 1, mean * off.y);
            add(k + kMomentTally + 2, mean * off.z);
            if (bounce <= settings.lobe_orders) {  // the flight after scattering `bounce` times
              add(k + kLobeTally + 2 * (bounce - 1), mean);
              add(k + kLobeTally + 2 * (bounce - 1) + 1, mean * glm::dot(d, l));
            }
          }
          if (c.medium < 0) break;  // escaped
        }
      }
    });
  });

  // The part of each cell where tentative collisions can happen (some brick's majorant > 0),
  // its centroid about the cell's centre and its variance per axis, in cells.
  std::vector<double> covered(n_cells, 0.0);
  std::vector<glm::dvec3> centroid(n_cells, glm::dvec3(0.0)), spread(n_cells, glm::dvec3(0.0));
  arena.execute([&] {
    tbb::parallel_for(0, nz, [&](int k) {
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          int hits = 0;
          glm::dvec3 sum(0.0), sum_sq(0.0);
          for (int s = 0; s < kSubsamples * kSubsamples * kSubsamples; ++s) {
            const glm::dvec3 f((s % kSubsamples + 0.5) / kSubsamples, ((s / kSubsamples) % kSubsamples + 0.5) / kSubsamples,
                               (s / (kSubsamples * kSubsamples) + 0.5) / kSubsamples);
            if (total_majorant(media, v.world_min + cell * (glm::dvec3(i, j, k) + f)) > 0.0) {
              ++hits;
              sum += f - 0.5;
              sum_sq += (f - 0.5) * (f - 0.5);
            }
          }
          const std::size_t q = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
          covered[q] = static_cast<double>(hits) / (kSubsamples * kSubsamples * kSubsamples);
          if (hits > 0) {
            centroid[q] = sum / static_cast<double>(hits);
            // Each subsample stands for a cube 1 / kSubsamples wide: its own variance adds.
            spread[q] = sum_sq / static_cast<double>(hits) - centroid[q] * centroid[q] +
                        1.0 / (12.0 * kSubsamples * kSubsamples);
          }
        }
    });
  });

  // Track length per volume (eq. MS-2): phi = (E A / N) sum(w l) / V, per unit irradiance E.
  const double scale = area_m2 / static_cast<double>(n) * quantum / (cell.x * cell.y * cell.z);
  std::vector<float> value(n_cells * kTallies, 0.0f);
  std::vector<char> known(n_cells, 0);
  // Calls f(r) for each cell r of the 3^3 neighbourhood of (i, j, k) inside the grid, itself included.
  auto for_neighbourhood = [&](int i, int j, int k, const auto& f) {
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ni = i + di, nj = j + dj, nk = k + dk;
          if (ni < 0 || ni >= nx || nj < 0 || nj >= ny || nk < 0 || nk >= nz) continue;
          f(static_cast<std::size_t>(ni) + static_cast<std::size_t>(nx) * (nj + static_cast<std::size_t>(ny) * nk));
        }
  };
  // A cell the cloud barely touches divides a few rare collisions by a small covered fraction:
  // a firefly. Below half coverage the cell pools its 3^3 neighbourhood instead, sum of tallies
  // over sum of covered fractions (a ratio estimator over more photons; measured: no specks).
  constexpr double kPoolBelow = 0.5;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t q = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
        if (!(covered[q] > 0.0)) continue;
        known[q] = 1;
        if (covered[q] >= kPoolBelow) {
          for (int c = 0; c < kTallies; ++c)
            value[q * kTallies + c] = static_cast<float>(scale * static_cast<double>(tally[q * kTallies + c].load()) / covered[q]);
          continue;
        }
        double area = 0.0, sum[kTallies] = {};
        for_neighbourhood(i, j, k, [&](std::size_t r) {
          area += covered[r];
          for (int c = 0; c < kTallies; ++c) sum[c] += static_cast<double>(tally[r * kTallies + c].load());
        });
        for (int c = 0; c < kTallies; ++c) value[q * kTallies + c] = static_cast<float>(scale * sum[c] / area);
      }
  // A rare flight through a thin brick (small majorant m, weight w / m per collision) could leave
  // one cell far brighter than every neighbour: a white blob where the eye sees it (measured: one
  // at the base of a tower of the default sky at 2^19 photons, faint at 2^21; 3x left a glow, 2x
  // none). The majorant's floor above now bounds each collision's weight; this clamp stays as
  // the guard against what photon noise is left. Scattered light
  // diffuses, so a cell with at least 6 known neighbours holds at most kSpike times their mean
  // fluence; above that all its tallies are scaled down together (its anisotropy kept).
  constexpr double kSpike = 2.0;
  {
    const std::vector<float> before = value;
    auto mean_fluence = [&](std::size_t r) {
      return (before[r * kTallies] + before[r * kTallies + 1] + before[r * kTallies + 2]) / 3.0;
    };
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const std::size_t q = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
          if (!known[q]) continue;
          double sum = 0.0;
          int count = 0;
          for_neighbourhood(i, j, k, [&](std::size_t r) {
            if (r == q || !known[r]) return;
            sum += mean_fluence(r);
            ++count;
          });
          const double own = mean_fluence(q);
          if (count < 6 || !(own > kSpike * sum / count)) continue;
          const double f = kSpike * (sum / count) / own;
          for (int c = 0; c < kTallies; ++c) value[q * kTallies + c] = static_cast<float>(before[q * kTallies + c] * f);
        }
  }
  // The flux and the second moment carry the view-dependent part, and their noise shows as white
  // specks where a cell's noisy flux happens to point at the eye (measured: one at seed 1 on
  // cumulus-mediocris, none at seed 2). They vary slowly in space: each known cell takes their
  // anisotropy over its known 3^3 neighbourhood: F = phi sum(F) / sum(phi), the same for Q (a
  // fluence-weighted mean of the neighbours' F / phi, so |F| <= phi still holds). The fluence
  // keeps its own cell's value.
  {
    const std::vector<float> before = value;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const std::size_t q = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
          if (!known[q]) continue;
          double sum[kTallies] = {}, phi = 0.0;
          for_neighbourhood(i, j, k, [&](std::size_t r) {
            if (!known[r]) return;
            phi += (before[r * kTallies] + before[r * kTallies + 1] + before[r * kTallies + 2]) / 3.0;  // F, Q: the channels' mean
            for (int c = 3; c < kMomentTally; ++c) sum[c] += before[r * kTallies + c];
          });
          const double own = (before[q * kTallies] + before[q * kTallies + 1] + before[q * kTallies + 2]) / 3.0;
          for (int c = 3; c < kMomentTally; ++c) value[q * kTallies + c] = phi > 0.0 ? static_cast<float>(own * sum[c] / phi) : 0.0f;
        }
  }
  // Eq. MS-4's fit where a cell has its own photons (not pooled): with phi(u) = phi_bar + g . (u - ubar)
  // over the covered part, the first moment about the centre M = phi_bar ubar + diag(spread) g,
  // so g = (M - phi_bar ubar) / spread per axis; limited so that the fit stays >= 0 over the cell.
  std::vector<float> fit(n_cells * 4, 0.0f);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t q = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
        if (!(covered[q] >= kPoolBelow)) continue;
        const double phi = (value[q * kTallies] + value[q * kTallies + 1] + value[q * kTallies + 2]) / 3.0;
        if (!(phi > 0.0)) continue;
        glm::dvec3 g(0.0);
        for (int ax = 0; ax < 3; ++ax)
          if (spread[q][ax] > 1e-3) g[ax] = (value[q * kTallies + kMomentTally + ax] - phi * centroid[q][ax]) / spread[q][ax];
        const double reach = glm::dot(glm::abs(g), 0.5 + glm::abs(centroid[q]));
        if (reach > phi) g *= phi / reach;
        const glm::dvec3 ubar = glm::dvec3(i, j, k) + 0.5 + centroid[q];
        for (int ax = 0; ax < 3; ++ax) fit[4 * q + ax] = static_cast<float>(g[ax]);
        fit[4 * q + 3] = static_cast<float>(glm::dot(g, ubar));
      }
  // Cells no flight can cross hold no cloud, but the trilinear lookup of a neighbour reads them:
  // they take the mean of their known face neighbours, ring by ring (two rings).
  for (int ring = 0; ring < 2; ++ring) {
    std::vector<char> next = known;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const std::size_t q = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
          if (known[q]) continue;
          const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
          int count = 0;
          double sum[kTallies] = {}, fit_sum[4] = {};
          for (const auto& b : nb) {
            if (b[0] < 0 || b[0] >= nx || b[1] < 0 || b[1] >= ny || b[2] < 0 || b[2] >= nz) continue;
            const std::size_t r = static_cast<std::size_t>(b[0]) + static_cast<std::size_t>(nx) * (b[1] + static_cast<std::size_t>(ny) * b[2]);
            if (!known[r]) continue;
            ++count;
            for (int c = 0; c < kTallies; ++c) sum[c] += value[r * kTallies + c];
            for (int c = 0; c < 4; ++c) fit_sum[c] += fit[4 * r + c];
          }
          if (count == 0) continue;
          // The mean of the neighbours' fits too (eq. MS-4 is linear in them): the lookups
          // between an edge cell and this one follow the edge cell's fit, not a constant.
          for (int c = 0; c < kTallies; ++c) value[q * kTallies + c] = static_cast<float>(sum[c] / count);
          for (int c = 0; c < 4; ++c) fit[4 * q + c] = static_cast<float>(fit_sum[c] / count);
          next[q] = 1;
        }
    known.swap(next);
  }
  v.fluence_rgb.resize(n_cells * 3);
  v.flux_xyz.resize(n_cells * 3);
  v.quadrupole.resize(n_cells * 5);
  v.lobes.assign(n_cells * 4, 0.0f);
  if (settings.fits) v.gradient = std::move(fit);
  v.light_direction = l;
  for (std::size_t q = 0; q < n_cells; ++q) {
    for (int c = 0; c < 3; ++c) {
      v.fluence_rgb[3 * q + c] = value[q * kTallies + c];
      v.flux_xyz[3 * q + c] = value[q * kTallies + 3 + c];
    }
    for (int c = 0; c < 5; ++c) v.quadrupole[5 * q + c] = value[q * kTallies + 6 + c];
    // Eq. MS-3's lobes: f_k = phi_k / phi, mu_k = (phi_k mean cosine to the sun) / phi_k.
    const double phi = (value[q * kTallies] + value[q * kTallies + 1] + value[q * kTallies + 2]) / 3.0;
    double room = 1.0;
    for (int o = 0; o < 2; ++o) {
      const double phi_k = value[q * kTallies + kLobeTally + 2 * o], along = value[q * kTallies + kLobeTally + 2 * o + 1];
      if (!(phi > 0.0 && phi_k > 0.0)) continue;
      const double f = std::min(phi_k / phi, room);
      room -= f;
      v.lobes[4 * q + 2 * o] = static_cast<float>(f);
      v.lobes[4 * q + 2 * o + 1] = static_cast<float>(std::clamp(along / phi_k, -0.95, 0.95));
    }
  }
  v.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return v;
}

}  // namespace nimbus::render

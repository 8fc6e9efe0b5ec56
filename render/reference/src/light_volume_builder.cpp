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

#include "nimbus/render/reference/light_volume_stages.hpp"
#include "traced_media.hpp"

namespace nimbus::render {

using namespace traced;
using namespace light_volume;

namespace {

constexpr std::size_t kMaxBytes = std::size_t{2} << 30;  // 2 GiB
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

namespace {

// The fixed-point tallies of weight x metres (integer sums do not depend on the order of the adds).
struct Tallies {
  double quantum = 0.0;  // metres of weighted track per unit
  std::vector<std::atomic<std::int64_t>> sum;  // kTallies per cell
};

// Each brick's majorant raised to one tentative collision per cell's width. A tentative collision
// stands for 1 / m metres of track, so in a brick of thin cloud (small majorant m) one flight's
// few collisions count kilometres: a cluster of cells that support each other past the spike
// clamp (measured: 2x2 cells at 4x their surroundings on the congestus tower's shadowed face, a
// white blob, 78 % of that case's squared error). Any m at least the extinction is a majorant, so
// a collision then stands for at most a cell's width of track.
void raise_majorants(std::vector<TracedCloud>& media, double shortest_cell_m) {
  for (TracedCloud& m : media)
    for (double& b : m.majorant)
      if (b > 0.0) b = std::max(b, 1.0 / shortest_cell_m);
}

// Adds one tentative collision at p (t along d) of a flight after `bounce` scatterings.
void tally_collision(Tallies& tallies, const LightVolume& v, const CellGrid& g, const std::vector<TracedCloud>& media,
                     const glm::dvec3& p, const glm::dvec3& d, const glm::dvec3& weight, int bounce, int lobe_orders,
                     const glm::dvec3& l) {
  const glm::dvec3 u = (p - v.world_min) / v.cell_m;  // in cells
  const glm::dvec3 ijk = glm::floor(u);
  // The bricks reach up to 7 voxels past a cloud's support, where only null collisions happen;
  // the grid covers the support alone, and a point beyond it is no cell's track (clamped into the
  // edge cells it made the stratus sheet's top layer 5.5x too bright).
  if (!(ijk.x >= 0.0 && ijk.y >= 0.0 && ijk.z >= 0.0 && ijk.x < g.nx && ijk.y < g.ny && ijk.z < g.nz)) return;
  const double m = total_majorant(media, p);
  if (!(m > 0.0)) return;
  const std::size_t k = g.index(int(ijk.x), int(ijk.y), int(ijk.z)) * kTallies;
  auto add = [&](std::size_t idx, double value) {
    tallies.sum[idx].fetch_add(std::llround(value / tallies.quantum), std::memory_order_relaxed);
  };
  const glm::dvec3 wt = weight / m;  // each tentative collision stands for 1 / m metres of track
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
  if (bounce <= lobe_orders) {  // the flight after scattering `bounce` times
    add(k + kLobeTally + 2 * (bounce - 1), mean);
    add(k + kLobeTally + 2 * (bounce - 1) + 1, mean * glm::dot(d, l));
  }
}

// Photon i's path from the launch rectangle: after its first real collision, every tentative
// collision of every flight is tallied, until it escapes, is absorbed or loses the roulette.
void trace_photon(std::int64_t i, Tallies& tallies, const LightVolume& v, const CellGrid& g,
                  const std::vector<TracedCloud>& media, const LaunchRect& rect, double shift_u, double shift_v,
                  double back_m, const LightVolumeSettings& settings, std::vector<double>& points) {
  PathRng rng(settings.seed, static_cast<std::uint64_t>(i));
  const double fi = static_cast<double>(i);
  // Positions on the rectangle: the R2 sequence (Roberts 2018), shifted per seed (Cranley-Patterson).
  const double x = std::fmod(shift_u + fi * 0.7548776662466927, 1.0);
  const double y = std::fmod(shift_v + fi * 0.5698402909980532, 1.0);
  glm::dvec3 o = rect.origin(x, y, back_m);
  glm::dvec3 d = rect.l;
  // The unscattered flight: single scattering is the slicer's own, so nothing is tallied.
  Collision c = collide(media, o, d, rng);
  if (c.medium < 0) return;
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
    for (double t : points)
      if (!(t > c.t)) tally_collision(tallies, v, g, media, o + t * d, d, weight, bounce, settings.lobe_orders, rect.l);
    if (c.medium < 0) break;  // escaped
  }
}

// Stage: the photons, on the arena's threads; deterministic per seed (photon i draws from its
// own stream, the tallies are integers).
Tallies trace_photons(const LightVolume& v, const CellGrid& g, const std::vector<TracedCloud>& media,
                      const LaunchRect& rect, const LightVolumeSettings& settings, tbb::task_arena& arena) {
  const double shortest = std::min({v.cell_m.x, v.cell_m.y, v.cell_m.z});
  const double widest = std::max({v.cell_m.x, v.cell_m.y, v.cell_m.z});
  Tallies tallies;
  tallies.quantum = 1e-9 * shortest;
  tallies.sum = std::vector<std::atomic<std::int64_t>>(g.cells() * kTallies);
  for (auto& t : tallies.sum) t.store(0, std::memory_order_relaxed);
  PathRng shift_rng(settings.seed, ~std::uint64_t{0});
  const double shift_u = shift_rng.uniform(), shift_v = shift_rng.uniform();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, settings.photons, 1024),
                      [&](const tbb::blocked_range<std::int64_t>& r) {
                        std::vector<double> points;
                        for (std::int64_t i = r.begin(); i < r.end(); ++i)
                          trace_photon(i, tallies, v, g, media, rect, shift_u, shift_v, widest, settings, points);
                      });
  });
  return tallies;
}

// Stage: each cell's covered part (light_volume_stages.hpp, Coverage), from kSubsamples^3 points.
Coverage coverage_of(const LightVolume& v, const CellGrid& g, const std::vector<TracedCloud>& media,
                     tbb::task_arena& arena) {
  Coverage cov;
  cov.covered.assign(g.cells(), 0.0);
  cov.centroid.assign(g.cells(), glm::dvec3(0.0));
  cov.spread.assign(g.cells(), glm::dvec3(0.0));
  arena.execute([&] {
    tbb::parallel_for(0, g.nz, [&](int k) {
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
          int hits = 0;
          glm::dvec3 sum(0.0), sum_sq(0.0);
          for (int s = 0; s < kSubsamples * kSubsamples * kSubsamples; ++s) {
            const glm::dvec3 f((s % kSubsamples + 0.5) / kSubsamples, ((s / kSubsamples) % kSubsamples + 0.5) / kSubsamples,
                               (s / (kSubsamples * kSubsamples) + 0.5) / kSubsamples);
            if (total_majorant(media, v.world_min + v.cell_m * (glm::dvec3(i, j, k) + f)) > 0.0) {
              ++hits;
              sum += f - 0.5;
              sum_sq += (f - 0.5) * (f - 0.5);
            }
          }
          const std::size_t q = g.index(i, j, k);
          cov.covered[q] = static_cast<double>(hits) / (kSubsamples * kSubsamples * kSubsamples);
          if (hits > 0) {
            cov.centroid[q] = sum / static_cast<double>(hits);
            // Each subsample stands for a cube 1 / kSubsamples wide: its own variance adds.
            cov.spread[q] = sum_sq / static_cast<double>(hits) - cov.centroid[q] * cov.centroid[q] +
                            1.0 / (12.0 * kSubsamples * kSubsamples);
          }
        }
    });
  });
  return cov;
}

}  // namespace

LightVolume build_light_volume(const std::vector<CloudVolume>& clouds, const Light& light,
                               const LightVolumeSettings& settings) {
  validate(light);
  if (light.kind != LightKind::Sun)
    throw std::invalid_argument("light volume light: photons come from the sun only; a lamp takes the octaves method of multiple scattering");
  LightVolume v = light_volume_grid(clouds, settings);
  if (light_volume_bytes(v) > kMaxBytes)
    throw std::length_error("light volume: " + std::to_string(v.size[0]) + "x" + std::to_string(v.size[1]) + "x" +
                            std::to_string(v.size[2]) + " cells would take " + std::to_string(light_volume_bytes(v) >> 20) +
                            " MiB, more than 2048");
  const auto start = std::chrono::steady_clock::now();
  const CellGrid g{v.size[0], v.size[1], v.size[2]};
  std::vector<TracedCloud> media = media_of(clouds);
  raise_majorants(media, std::min({v.cell_m.x, v.cell_m.y, v.cell_m.z}));
  const LaunchRect rect = launch_rect(v, light.direction_to_sun);
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);

  const Tallies tallies = trace_photons(v, g, media, rect, settings, arena);
  const Coverage coverage = coverage_of(v, g, media, arena);
  // Track length per volume (eq. MS-2): phi = (E A / N) sum(w l) / V, per unit irradiance E.
  const double scale = rect.area_m2() / static_cast<double>(settings.photons) * tallies.quantum /
                       (v.cell_m.x * v.cell_m.y * v.cell_m.z);
  CellValues values = cell_values(g, tallies.sum, coverage.covered, scale);
  clamp_spikes(g, values);
  smooth_anisotropy(g, values);
  std::vector<float> fit = linear_fits(g, values, coverage);
  fill_empty_rings(g, values, fit);
  pack_light_volume(values, std::move(fit), settings.fits, rect.l, v);
  v.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return v;
}

}  // namespace nimbus::render

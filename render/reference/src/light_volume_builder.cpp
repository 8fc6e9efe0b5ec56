// The light volume's photon tracer (light_volume_builder.hpp).
#include "nimbus/render/reference/light_volume_builder.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <iterator>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nimbus/render/reference/light_volume_diffusion.hpp"
#include "nimbus/render/reference/light_volume_stages.hpp"
#include "traced_media.hpp"
#include "nimbus/base/cancel.hpp"

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

// A stretch of a flight inside bricks with a majorant (metres along it): where the cloud may have
// medium, and so where a flight's track is tallied.
struct Span {
  double a, b;
};

// Delta tracking in one cloud as TracedCloud::free_flight, recording the stretches of the flight
// inside its bricks with a majorant, up to the real collision, into `spans`. Returns the real
// collision's distance or +inf.
// `scale` multiplies the cloud's extinction (the similar medium's sigma_t' / sigma_t; 1: the cloud).
double free_flight_recorded(const TracedCloud& c, const glm::dvec3& o, const glm::dvec3& d, double t1, double scale,
                            PathRng& rng, std::vector<Span>& spans) {
  double hit = kInf;
  c.march(o, d, 0.0, t1, [&](double s0, double s1, double m_cloud, const glm::dvec3& lo, const glm::dvec3& ld) {
    if (m_cloud <= 0.0) return true;
    const double m = m_cloud * scale;
    double t = s0;
    while (true) {
      t -= std::log(1.0 - rng.uniform()) / m;
      if (t >= s1) {
        spans.push_back({s0, s1});
        return true;
      }
      if (rng.uniform() * m < scale * c.sigma_t(lo, ld, t)) {
        spans.push_back({s0, t});
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
  v.diffusion_depth = settings.diffusion_depth;
  v.similarity_depth = settings.similarity_depth;
  return v;
}

std::size_t light_volume_bytes(const LightVolume& grid) {
  // Tallies (int64), the covered fraction (double), the values and the result (float); with the
  // deep light diffused, the cells' optics, sources, the linear system and its solution (about
  // 400 bytes a cell, light_volume_diffusion.cpp).
  return grid.cells() * (kTallies * sizeof(std::int64_t) + sizeof(double) + 2 * kTallies * sizeof(float) + 1 +
                         (grid.diffusion_depth > 0.0 ? 400 : 0));
}

namespace {

// The fixed-point tallies of weight x metres (integer sums do not depend on the order of the adds).
struct Tallies {
  double quantum = 0.0;  // metres of weighted track per unit
  std::vector<std::int64_t> sum;  // kTallies per cell
  // With diffused deep light: the weight that scatters in a deep cell, RGB per cell, in units of
  // kSourceQuantum.
  std::vector<std::int64_t> source;
};
constexpr double kSourceQuantum = 1e-9;
// Each thread tallies into its own arrays, merged after (plain adds: a third less time than
// atomic adds into one array, measured on the main job's volume), unless they would take more
// than this together; then every thread adds atomically into one.
constexpr std::size_t kThreadTallyBytes = std::size_t{512} << 20;

// Tally arrays take up to kThreadTallyBytes: zeroing or adding them takes tenths of a second, so
// both go a chunk at a time, with a poll of the call's stop between chunks (cancel.hpp).
constexpr std::size_t kPolledChunk = std::size_t{1} << 20;  // 8 MiB of int64
std::vector<std::int64_t> zeroed_polled(std::size_t n, const std::stop_token& stop) {
  std::vector<std::int64_t> a;
  a.reserve(n);
  while (a.size() < n) {
    throw_if_stopped(stop);
    a.resize(std::min(n, a.size() + kPolledChunk), 0);
  }
  return a;
}
void add_polled(std::vector<std::int64_t>& to, const std::vector<std::int64_t>& from, const std::stop_token& stop) {
  for (std::size_t i = 0; i < from.size(); ++i) {
    if (i % kPolledChunk == 0) throw_if_stopped(stop);
    to[i] += from[i];
  }
}

// Where one thread's tallies go.
struct TallySink {
  std::int64_t* sum = nullptr;
  std::int64_t* source = nullptr;
  bool shared = false;  // the arrays are every thread's: add atomically
  double per_metre = 0.0;  // 1 / Tallies::quantum: units per metre of weighted track
  static void add(std::int64_t* a, std::size_t i, double units, bool shared) {
    const std::int64_t x = static_cast<std::int64_t>(units + (units >= 0.0 ? 0.5 : -0.5));  // to nearest
    if (shared)
      std::atomic_ref<std::int64_t>(a[i]).fetch_add(x, std::memory_order_relaxed);
    else
      a[i] += x;
  }
  void add_units(std::size_t i, double units) const { add(sum, i, units, shared); }
  void add_source(std::size_t i, double weight) const { add(source, i, weight / kSourceQuantum, shared); }
};

// The cell that world point p lies in, or false outside the grid.
bool cell_at(const LightVolume& v, const CellGrid& g, const glm::dvec3& p, std::size_t& q) {
  const glm::dvec3 ijk = glm::floor((p - v.world_min) / v.cell_m);
  if (!(ijk.x >= 0.0 && ijk.y >= 0.0 && ijk.z >= 0.0 && ijk.x < g.nx && ijk.y < g.ny && ijk.z < g.nz)) return false;
  q = g.index(int(ijk.x), int(ijk.y), int(ijk.z));
  return true;
}

// Where photons hand their light to diffusion: the deep cells, and the cells' mean optics (a
// source lands only in cells with medium, the solve's unknowns).
struct Handover {
  std::vector<char> deep;
  const CellMedium* medium = nullptr;
  bool on() const { return !deep.empty(); }
  bool deep_at(const LightVolume& v, const CellGrid& g, const glm::dvec3& p) const {
    std::size_t q = 0;
    return cell_at(v, g, p, q) && deep[q] != 0;
  }
};

// A cloud's similar medium (LightVolumeSettings::similarity_depth): the same absorption
// sigma_a = sigma_t (1 - a), isotropic scattering with sigma_s' = sigma_s (1 - g), g the phase's
// mean cosine, so sigma_t' = sigma_t (1 - a g) and a' = a (1 - g) / (1 - a g) (the similarity
// relation, exact for diffusion: its diffusion coefficient 1 / (3 sigma_tr) and absorption are
// the cloud's own; Wyman, Patterson & Wilson 1989). Grey extinction takes the channels' mean a.
struct SimilarMedium {
  double extinction_scale = 1.0;  // sigma_t' / sigma_t
  glm::dvec3 albedo{1.0};         // a', per channel
};

// Where photons fly in the similar media: the cells deep enough (empty: nowhere).
struct Similarity {
  std::vector<SimilarMedium> media;  // per cloud
  std::vector<char> deep;            // per cell
  bool at(const LightVolume& v, const CellGrid& g, const glm::dvec3& p) const {
    std::size_t q = 0;
    return !deep.empty() && cell_at(v, g, p, q) && deep[q] != 0;
  }
};
const Phase kIsotropic;

std::vector<SimilarMedium> similar_media(const std::vector<CloudVolume>& clouds) {
  std::vector<SimilarMedium> out;
  for (const CloudVolume& c : clouds) {
    const double g = phase_legendre(c.optics.phase, 1);
    const glm::dvec3 a = c.optics.albedo;
    const double scale = 1.0 - (a.x + a.y + a.z) / 3.0 * g;  // > 0: a <= 1, |g| < 1
    out.push_back({scale, glm::min(glm::dvec3(1.0), a * (1.0 - g) / scale)});
  }
  return out;
}

// Where the light that scatters at p, arriving along d, is centred: a phase of mean cosine g sends
// it on along d, by g / sigma_t in its first flight, g^2 / sigma_t in its second and so on, in
// all g / (sigma_t (1 - g)) (an unabsorbed walk in a uniform medium). Diffusion's source is
// isotropic about its point, so it is placed there: at the collision itself the diffused light
// lay a transport mean free path short of where the photons carry it (measured on a ball 7.4
// transport mean free paths in radius under HG 0.7: its core 11.5 % too dark).
glm::dvec3 source_centre(const LightVolume& v, const CellGrid& g, const Handover& h, const glm::dvec3& p,
                         const glm::dvec3& d, double mean_cosine) {
  std::size_t q = 0;
  if (!cell_at(v, g, p, q)) return p;
  const double sigma_t = h.medium->sigma_t[q];
  if (!(sigma_t > 0.0) || !(mean_cosine > 0.0)) return p;
  return p + d * (std::min(mean_cosine, 0.95) / (sigma_t * (1.0 - std::min(mean_cosine, 0.95))));
}

// Adds a photon's scattered weight at p to the diffusion's source, shared among the 8 cells whose
// centres surround p by trilinear weights (cloud-in-cell): a source placed at its cell's centre
// would move by up to half a cell, and where a cell is a sizeable part of the diffusion length
// that changes how much of it escapes (measured on a slab 30 mean free paths thick in cells of
// 3.9: the diffused fluence 20-30 % high). Weights on cells without medium, or past the grid, go
// to the others.
bool tally_source(const TallySink& sink, const LightVolume& v, const CellGrid& g, const Handover& h, const glm::dvec3& p,
                  const glm::dvec3& weight) {
  const glm::dvec3 u = (p - v.world_min) / v.cell_m - 0.5;
  const glm::dvec3 base = glm::floor(u), f = u - base;
  std::size_t cell[8];
  double w[8], total = 0.0;
  int n = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const int i = int(base.x) + (corner & 1), j = int(base.y) + ((corner >> 1) & 1), k = int(base.z) + (corner >> 2);
    if (i < 0 || j < 0 || k < 0 || i >= g.nx || j >= g.ny || k >= g.nz) continue;
    const std::size_t c = g.index(i, j, k);
    if (!(h.medium->sigma_t[c] > 0.0)) continue;
    const double wc = ((corner & 1) ? f.x : 1.0 - f.x) * (((corner >> 1) & 1) ? f.y : 1.0 - f.y) * ((corner >> 2) ? f.z : 1.0 - f.z);
    if (!(wc > 0.0)) continue;
    cell[n] = c;
    w[n++] = wc;
    total += wc;
  }
  if (!(total > 0.0)) return false;  // no cell with medium around p
  for (int m = 0; m < n; ++m)
    for (int c = 0; c < 3; ++c)
      sink.add_source(cell[m] * 3 + c, weight[c] * w[m] / total);
  return true;
}

// Adds a flight's track after `bounce` scatterings, along d from o up to `end`, in the cells it
// crosses inside the clouds' bricks (`spans`, of one or more clouds): each cell gets the exact
// length of the flight inside it and its first moment (eq. MS-2's track-length estimator with the
// track itself, not its tentative collisions, which only sampled it: measured, less photon noise
// for the same photons). Within a flight the weight and the direction hold, so a cell's tallies
// follow from its track and moment once (a flight that leaves a cell and enters it again, between
// two clouds' bricks, is added per run).
void tally_flight(const TallySink& sink, const LightVolume& v, const CellGrid& g, const glm::dvec3& o, const glm::dvec3& d,
                  double end, std::vector<Span>& spans, bool several_clouds, const glm::dvec3& weight, int bounce,
                  int lobe_orders, const glm::dvec3& l) {
  constexpr std::size_t kNone = ~std::size_t{0};
  std::size_t cell = kNone;
  double track = 0.0;
  glm::dvec3 moment(0.0);
  const double w_mean = (weight.x + weight.y + weight.z) / 3.0;
  const auto flush = [&] {
    if (cell == kNone || !(track > 0.0)) return;
    const std::size_t k = cell * kTallies;
    // In the tallies' fixed-point units (a multiply, not a divide per tally).
    const double units = track * sink.per_metre;
    const glm::dvec3 wt = weight * units;
    sink.add_units(k + 0, wt.x);
    sink.add_units(k + 1, wt.y);
    sink.add_units(k + 2, wt.z);
    const double mean = w_mean * units;
    sink.add_units(k + 3, mean * d.x);
    sink.add_units(k + 4, mean * d.y);
    sink.add_units(k + 5, mean * d.z);
    // The traceless second moment: w (d d^T - I / 3).
    sink.add_units(k + 6, mean * (d.x * d.x - 1.0 / 3.0));
    sink.add_units(k + 7, mean * (d.y * d.y - 1.0 / 3.0));
    sink.add_units(k + 8, mean * d.x * d.y);
    sink.add_units(k + 9, mean * d.x * d.z);
    sink.add_units(k + 10, mean * d.y * d.z);
    const glm::dvec3 m = (w_mean * sink.per_metre) * moment;
    sink.add_units(k + kMomentTally + 0, m.x);
    sink.add_units(k + kMomentTally + 1, m.y);
    sink.add_units(k + kMomentTally + 2, m.z);
    if (bounce <= lobe_orders) {  // the flight after scattering `bounce` times
      sink.add_units(k + kLobeTally + 2 * (bounce - 1), mean);
      sink.add_units(k + kLobeTally + 2 * (bounce - 1) + 1, mean * glm::dot(d, l));
    }
  };
  // One span per stretch of bricks that touch (one walk of the cells each), and several clouds'
  // spans, which overlap where their bricks do, as their union, in order.
  if (several_clouds) std::sort(spans.begin(), spans.end(), [](const Span& x, const Span& y) { return x.a < y.a; });
  std::size_t n = 0;
  for (const Span& s : spans) {
    if (n > 0 && s.a <= spans[n - 1].b)
      spans[n - 1].b = std::max(spans[n - 1].b, s.b);
    else
      spans[n++] = s;
  }
  spans.resize(n);
  // The flight in cells (traced::walk_cells, Amanatides & Woo 1987).
  const glm::dvec3 per_cell = 1.0 / v.cell_m;
  const glm::dvec3 uo = (o - v.world_min) * per_cell, ud = d * per_cell;
  const int cells[3] = {g.nx, g.ny, g.nz};
  for (const Span& s : spans) {
    // Only track inside the grid is tallied: the bricks reach up to 7 voxels past a cloud's
    // support, and that margin's track clamped into the edge cells made the stratus sheet's top
    // layer 5.5x too bright.
    walk_cells(uo, ud, cells, s.a, std::min(s.b, end), [&](const glm::ivec3& ijk, double s0, double s1) {
      const std::size_t q = g.index(ijk.x, ijk.y, ijk.z);
      if (q != cell) {
        flush();
        cell = q;
        track = 0.0;
        moment = glm::dvec3(0.0);
      }
      const double length = s1 - s0;
      track += length;
      moment += length * (uo + 0.5 * (s0 + s1) * ud - glm::dvec3(ijk) - 0.5);  // the part's centre, in the cell
      return true;
    });
  }
  flush();
}

// Photon i's position on the launch rectangle, in [0, 1)^2: the R2 sequence (Roberts 2018),
// shifted per seed (Cranley-Patterson).
glm::dvec2 launch_point(std::int64_t i, double shift_u, double shift_v) {
  // x - floor(x) is exact, as fmod(x, 1) is, and cheaper (fmod had 1.3 % of the build's profile).
  const double fi = static_cast<double>(i);
  const double x = shift_u + fi * 0.7548776662466927, y = shift_v + fi * 0.5698402909980532;
  return {x - std::floor(x), y - std::floor(y)};
}

// Photon i's path from the launch rectangle: after its first real collision, every flight's
// track is tallied, until it escapes, is absorbed or loses the roulette; or,
// where `deep` is given, until it scatters (after its lobe orders) in a deep cell, where its
// scattered weight becomes the diffusion's source instead.
void trace_photon(std::int64_t i, const TallySink& sink, const LightVolume& v, const CellGrid& g,
                  const std::vector<TracedCloud>& media, const Similarity& similar, const LaunchRect& rect,
                  double shift_u, double shift_v, double back_m, const LightVolumeSettings& settings,
                  const Handover& handover, std::vector<Span>& spans) {
  PathRng rng(settings.seed, static_cast<std::uint64_t>(i));
  const glm::dvec2 xy = launch_point(i, shift_u, shift_v);
  glm::dvec3 o = rect.origin(xy.x, xy.y, back_m);
  glm::dvec3 d = rect.l;
  // The unscattered flight: single scattering is the slicer's own, so nothing is tallied.
  Collision c = collide(media, o, d, rng);
  if (c.medium < 0) return;
  glm::dvec3 weight(1.0);
  bool in_similar = false;  // the flight that reached this collision was the similar media's
  for (int bounce = 1; bounce < 100000; ++bounce) {
    const std::size_t medium = static_cast<std::size_t>(c.medium);
    const CloudVolume& hit = *media[medium].cloud;
    o += c.t * d;
    weight *= in_similar ? similar.media[medium].albedo : hit.optics.albedo;
    if (handover.on() && bounce > settings.lobe_orders && handover.deep_at(v, g, o)) {
      const glm::dvec3 centre = source_centre(v, g, handover, o, d, phase_legendre(hit.optics.phase, 1));
      if (!tally_source(sink, v, g, handover, centre, weight)) tally_source(sink, v, g, handover, o, weight);
      break;
    }
    if (bounce >= 16 && !survives_roulette(weight, rng)) break;  // as the path tracer
    if (!(std::max({weight.x, weight.y, weight.z}) > 0.0)) break;
    d = sample_phase(in_similar ? kIsotropic : hit.optics.phase, d, rng);
    // The next flight, every cloud's stretches inside its bricks recorded; the nearest real
    // collision ends it. Past the lobe orders, from a deep cell, in the similar media.
    in_similar = bounce > settings.lobe_orders && similar.at(v, g, o);
    spans.clear();
    c = Collision{};
    for (std::size_t j = 0; j < media.size(); ++j) {
      const double scale = in_similar ? similar.media[j].extinction_scale : 1.0;
      const double t = free_flight_recorded(media[j], o, d, c.t, scale, rng, spans);
      if (t < c.t) {
        c.t = t;
        c.medium = static_cast<int>(j);
      }
    }
    tally_flight(sink, v, g, o, d, c.t, spans, media.size() > 1, weight, bounce, settings.lobe_orders, rect.l);
    if (c.medium < 0) break;  // escaped
  }
}

// Photons per batch of trace_photons, and the Z curve's bins per side of the launch rectangle.
constexpr std::int64_t kBatch = std::int64_t{1} << 18;
constexpr int kOrderBits = 6;

// The offsets 0..count-1 of photons first.. in the order of their launch points' bins along a Z
// curve (a counting sort; within a bin, by index).
void spatial_order(std::int64_t first, std::int64_t count, double shift_u, double shift_v,
                   std::vector<std::uint32_t>& order) {
  constexpr int kSide = 1 << kOrderBits;
  const auto morton = [](int x, int y) {
    std::uint32_t key = 0;
    for (int b = 0; b < kOrderBits; ++b) key |= ((x >> b & 1u) << (2 * b)) | ((y >> b & 1u) << (2 * b + 1));
    return key;
  };
  std::vector<std::uint32_t> key(static_cast<std::size_t>(count));
  std::vector<std::uint32_t> start(kSide * kSide + 1, 0);
  for (std::int64_t j = 0; j < count; ++j) {
    const glm::dvec2 xy = launch_point(first + j, shift_u, shift_v);
    const int x = std::min(kSide - 1, static_cast<int>(xy.x * kSide));
    const int y = std::min(kSide - 1, static_cast<int>(xy.y * kSide));
    key[static_cast<std::size_t>(j)] = morton(x, y);
    ++start[key[static_cast<std::size_t>(j)] + 1];
  }
  for (int b = 0; b < kSide * kSide; ++b) start[b + 1] += start[b];
  order.resize(static_cast<std::size_t>(count));
  for (std::int64_t j = 0; j < count; ++j)
    order[start[key[static_cast<std::size_t>(j)]]++] = static_cast<std::uint32_t>(j);
}

// Stage: the photons, on the arena's threads, a range of them per call; deterministic per seed
// (photon i draws from its own stream, the tallies are integers), so photons traced over several
// calls sum to the same tallies as in one.
class PhotonTallies {
 public:
  PhotonTallies(const CellGrid& g, const LightVolume& v, bool source, const LightVolumeSettings& settings,
                std::size_t threads, const std::stop_token& stop)
      : n_sum_(g.cells() * kTallies), n_source_(source ? g.cells() * 3 : 0) {
    quantum_ = 1e-9 * std::min({v.cell_m.x, v.cell_m.y, v.cell_m.z});
    PathRng shift_rng(settings.seed, ~std::uint64_t{0});
    shift_u_ = shift_rng.uniform();
    shift_v_ = shift_rng.uniform();
    shared_ = threads * (n_sum_ + n_source_) * sizeof(std::int64_t) > kThreadTallyBytes;
    if (shared_) {
      all_.sum = zeroed_polled(n_sum_, stop);
      all_.source = zeroed_polled(n_source_, stop);
    }
  }

  // Traces photons first..end - 1.
  void trace(std::int64_t first_photon, std::int64_t end, const LightVolume& v, const CellGrid& g,
             const std::vector<TracedCloud>& media, const Similarity& similar, const LaunchRect& rect,
             const LightVolumeSettings& settings, const Handover& handover, tbb::task_arena& arena,
             const std::stop_token& stop) {
    const double widest = std::max({v.cell_m.x, v.cell_m.y, v.cell_m.z});
    // Photons go a batch at a time, each batch in the order of their launch points along a Z curve
    // over the rectangle (Morton 1966), so that a thread's photons in a row walk the same cells and
    // find the tallies and the density in its cache. The set of photons is the same, so are the
    // integer sums.
    std::vector<std::uint32_t> order;
    for (std::int64_t first = first_photon; first < end; first += kBatch) {
      const std::int64_t count = std::min<std::int64_t>(kBatch, end - first);
      spatial_order(first, count, shift_u_, shift_v_, order);
      arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, count, 1024), [&](const tbb::blocked_range<std::int64_t>& r) {
          const TallySink sink = sink_of_this_thread(stop);
          std::vector<Span> spans;
          for (std::int64_t i = r.begin(); i < r.end(); ++i) {
            // Every 1024 photons (cancel.hpp): the auto partitioner hands a task many grains of
            // 1024 at once, so a poll per task could wait for seconds.
            if (((i - r.begin()) & 1023) == 0) throw_if_stopped(stop);
            trace_photon(first + order[static_cast<std::size_t>(i)], sink, v, g, media, similar, rect, shift_u_,
                         shift_v_, widest, settings, handover, spans);
          }
        });
      });
    }
  }

  // The sums of every thread's tallies. Integer sums: the same whatever thread tallied what.
  // `consume`: no more photons follow, and the first thread's arrays become the sums (no third
  // zeroed copy); otherwise a copy.
  Tallies sums(bool consume, const std::stop_token& stop) {
    Tallies out;
    out.quantum = quantum_;
    if (shared_) {
      out.sum = consume ? std::move(all_.sum) : all_.sum;
      out.source = consume ? std::move(all_.source) : all_.source;
      return out;
    }
    for (Own& mine : own_) {
      if (mine.sum.empty()) continue;
      if (out.sum.empty()) {
        out.sum = consume ? std::move(mine.sum) : mine.sum;
        out.source = consume ? std::move(mine.source) : mine.source;
        continue;
      }
      add_polled(out.sum, mine.sum, stop);
      add_polled(out.source, mine.source, stop);
    }
    if (out.sum.empty()) {  // no photon was traced
      out.sum = zeroed_polled(n_sum_, stop);
      out.source = zeroed_polled(n_source_, stop);
    }
    return out;
  }

 private:
  struct Own {
    std::vector<std::int64_t> sum, source;
  };
  TallySink sink_of_this_thread(const std::stop_token& stop) {
    if (shared_) return TallySink{all_.sum.data(), all_.source.data(), true, 1.0 / quantum_};
    Own& mine = own_.local();
    if (mine.sum.empty()) {
      mine.sum = zeroed_polled(n_sum_, stop);
      mine.source = zeroed_polled(n_source_, stop);
    }
    return TallySink{mine.sum.data(), mine.source.data(), false, 1.0 / quantum_};
  }

  std::size_t n_sum_ = 0, n_source_ = 0;
  double quantum_ = 0.0;
  double shift_u_ = 0.0, shift_v_ = 0.0;  // the launch sequence's shift (Cranley-Patterson)
  // Each thread tallies into its own arrays (Own), unless they would take more than
  // kThreadTallyBytes together; then every thread adds atomically into all_.
  bool shared_ = false;
  Own all_;
  tbb::enumerable_thread_specific<Own> own_;
};

// Stage: each cell's covered part (light_volume_stages.hpp, Coverage), from kSubsamples^3 points.
Coverage coverage_of(const LightVolume& v, const CellGrid& g, const std::vector<TracedCloud>& media,
                     tbb::task_arena& arena, const std::stop_token& stop) {
  Coverage cov;
  cov.covered.assign(g.cells(), 0.0);
  cov.centroid.assign(g.cells(), glm::dvec3(0.0));
  cov.spread.assign(g.cells(), glm::dvec3(0.0));
  arena.execute([&] {
    tbb::parallel_for(0, g.nz, [&](int k) {
      for (int j = 0; j < g.ny; ++j) {
        throw_if_stopped(stop);  // a row of cells at a time (cancel.hpp)
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
      }
    });
  });
  return cov;
}

// Stage: the diffused light (light_volume_diffusion.hpp) added to the cells' values: its fluence,
// its flux F = -D grad phi (the channels' mean) and, for eq. MS-4's fits, the first moment a
// linear fluence with its gradient has over the covered part; its second moment is 0 and it is in
// no lobe (it has scattered more often than the lobe orders).
void add_diffused_light(const CellGrid& g, LightVolume& v, const CellMedium& medium,
                         const std::vector<std::int64_t>& source, double q_scale, const Coverage& cov,
                         CellValues& values, const std::stop_token& stop) {
  std::vector<glm::dvec3> q(g.cells());
  for (std::size_t c = 0; c < g.cells(); ++c)
    for (int ch = 0; ch < 3; ++ch) q[c][ch] = q_scale * static_cast<double>(source[3 * c + ch]);
  const DiffusedLight light = solve_diffusion(g, v.cell_m, medium, q, 1e-6, 4000, stop);
  v.diffusion_iterations = light.iterations;
  for (std::size_t c = 0; c < g.cells(); ++c) {
    if (!values.known[c]) continue;
    float* value = &values.value[c * kTallies];
    for (int ch = 0; ch < 3; ++ch) value[ch] += static_cast<float>(light.fluence[c][ch]);
    const glm::dvec3 F = (light.flux[0][c] + light.flux[1][c] + light.flux[2][c]) / 3.0;
    for (int a = 0; a < 3; ++a) value[3 + a] += static_cast<float>(F[a]);
    const double phi = (light.fluence[c].x + light.fluence[c].y + light.fluence[c].z) / 3.0;
    for (int a = 0; a < 3; ++a)
      value[kMomentTally + a] += static_cast<float>(phi * cov.centroid[c][a] + cov.spread[c][a] * light.gradient[c][a]);
  }
}

}  // namespace

// What a setup holds: the clouds (the media point into them), the grid, the media, the cells'
// coverage and medium, and where photons hand over to diffusion or fly in the similar media.
struct LightVolumeSetup::Data {
  std::shared_ptr<const std::vector<CloudVolume>> clouds;  // may alias a caller's list without owning it
  LightVolumeSettings settings;                            // those it was made for
  LightVolume grid;
  CellGrid g;
  std::vector<TracedCloud> media;
  Coverage coverage;
  CellMedium medium;
  Handover handover;  // its medium points at `medium`: a Data never moves (held by pointer)
  Similarity similar;
  double seconds = 0.0;
};

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string grid_text(const LightVolume& v) {
  return std::to_string(v.size[0]) + "x" + std::to_string(v.size[1]) + "x" + std::to_string(v.size[2]);
}

}  // namespace

LightVolumeSetup::LightVolumeSetup(std::shared_ptr<const std::vector<CloudVolume>> clouds, const LightVolumeSettings& settings)
    : d_(std::make_unique<Data>()) {
  if (!clouds) throw std::invalid_argument("light volume clouds: none given");
  Data& d = *d_;
  d.clouds = std::move(clouds);
  d.settings = settings;
  d.grid = light_volume_grid(*d.clouds, settings);
  const LightVolume& v = d.grid;
  if (light_volume_bytes(v) > kMaxBytes)
    throw std::length_error("light volume: " + grid_text(v) + " cells would take " + std::to_string(light_volume_bytes(v) >> 20) +
                            " MiB, more than 2048");
  const auto start = std::chrono::steady_clock::now();
  d.g = CellGrid{v.size[0], v.size[1], v.size[2]};
  d.media = media_of(*d.clouds);
  const int concurrency = settings.threads > 0 ? settings.threads : int{tbb::task_arena::automatic};
  tbb::task_arena arena(concurrency);
  const std::stop_token stop = current_stop_token();  // this call's, taken on its own thread (cancel.hpp)
  d.coverage = coverage_of(v, d.g, d.media, arena, stop);
  // Where light diffuses (diffusion_depth > 0): the cells deep inside, from the cells' mean optics.
  // Where photons fly in the similar media (similarity_depth > 0): the cells deep enough.
  if (settings.diffusion_depth > 0.0 || settings.similarity_depth > 0.0)
    arena.execute([&] { d.medium = cell_medium(v, d.g, *d.clouds); });
  if (settings.diffusion_depth > 0.0) {
    d.handover.deep = cells_deeper_than(d.g, v.cell_m, d.medium, settings.diffusion_depth);
    d.handover.medium = &d.medium;
  }
  d.similar = Similarity{similar_media(*d.clouds), {}};
  if (settings.similarity_depth > 0.0) d.similar.deep = cells_deeper_than(d.g, v.cell_m, d.medium, settings.similarity_depth);
  d.seconds = seconds_since(start);
}

LightVolumeSetup::~LightVolumeSetup() = default;
const LightVolume& LightVolumeSetup::grid() const { return d_->grid; }
double LightVolumeSetup::seconds() const { return d_->seconds; }

bool LightVolumeSetup::fits(const LightVolumeSettings& settings) const {
  const Data& d = *d_;
  if (settings.diffusion_depth != d.settings.diffusion_depth || settings.similarity_depth != d.settings.similarity_depth)
    return false;
  const LightVolume grid = light_volume_grid(*d.clouds, settings);
  return std::equal(std::begin(grid.size), std::end(grid.size), std::begin(d.grid.size)) && grid.world_min == d.grid.world_min && grid.cell_m == d.grid.cell_m;
}

// Everything a build holds between its calls: its setup (the grid, the media, the cells'
// coverage and medium), the launch rectangle, and the photons' tallies so far.
struct LightVolumeBuild::State {
  explicit State(std::shared_ptr<const LightVolumeSetup> made)
      : setup(std::move(made)),
        grid(setup->d_->grid),
        g(setup->d_->g),
        media(setup->d_->media),
        coverage(setup->d_->coverage),
        medium(setup->d_->medium),
        handover(setup->d_->handover),
        similar(setup->d_->similar) {}
  std::shared_ptr<const LightVolumeSetup> setup;
  const LightVolume& grid;
  const CellGrid& g;
  const std::vector<TracedCloud>& media;
  const Coverage& coverage;
  const CellMedium& medium;
  const Handover& handover;
  const Similarity& similar;
  LightVolumeSettings settings;
  LaunchRect rect;
  std::unique_ptr<tbb::task_arena> arena;
  std::unique_ptr<PhotonTallies> tallies;
  std::int64_t traced = 0;
  double seconds = 0.0;  // spent on the build so far
  bool broken = false;   // a trace ended part-way (stopped, or out of memory): its tallies hold part of a share
  void check_whole() const {
    if (broken) throw std::logic_error("light volume build: a trace of it ended part-way (stopped or failed); start a new build");
  }
};

namespace {

// The light, checked: photons come from the sun only.
const Light& sun_only(const Light& light) {
  validate(light);
  if (light.kind != LightKind::Sun)
    throw std::invalid_argument("light volume light: photons come from the sun only; a lamp takes the octaves method of multiple scattering");
  return light;
}

// A setup over a caller's list, without copying or owning it (the caller keeps it alive).
std::shared_ptr<const LightVolumeSetup> borrowed_setup(const std::vector<CloudVolume>& clouds, const LightVolumeSettings& settings) {
  return std::make_shared<const LightVolumeSetup>(std::shared_ptr<const std::vector<CloudVolume>>(std::shared_ptr<void>(), &clouds),
                                                  settings);
}

}  // namespace

LightVolumeBuild::LightVolumeBuild(const std::vector<CloudVolume>& clouds, const Light& light,
                                   const LightVolumeSettings& settings)
    : LightVolumeBuild((sun_only(light), borrowed_setup(clouds, settings)), light, settings) {}

LightVolumeBuild::LightVolumeBuild(std::shared_ptr<const LightVolumeSetup> setup, const Light& light,
                                   const LightVolumeSettings& settings) {
  sun_only(light);
  if (!setup) throw std::invalid_argument("light volume build: no setup given");
  if (!setup->fits(settings))
    throw std::invalid_argument("light volume build: its settings need another grid or depths than the setup's " +
                                grid_text(setup->grid()) + " cells");
  s_ = std::make_unique<State>(std::move(setup));
  State& s = *s_;
  const auto start = std::chrono::steady_clock::now();
  s.settings = settings;
  s.rect = launch_rect(s.grid, light.direction_to_sun);
  const int concurrency = settings.threads > 0 ? settings.threads : int{tbb::task_arena::automatic};
  s.arena = std::make_unique<tbb::task_arena>(concurrency);
  const std::size_t threads = static_cast<std::size_t>(std::max(1, s.arena->max_concurrency()));
  s.tallies = std::make_unique<PhotonTallies>(s.g, s.grid, s.handover.on(), settings, threads, current_stop_token());
  // The build's time includes its setup's, as when it was made for this build alone.
  s.seconds = s.setup->seconds() + seconds_since(start);
}

LightVolumeBuild::~LightVolumeBuild() = default;

std::int64_t LightVolumeBuild::traced() const { return s_->traced; }
std::int64_t LightVolumeBuild::photons() const { return s_->settings.photons; }

std::int64_t LightVolumeBuild::trace(std::int64_t photons) {
  if (photons < 1) throw std::invalid_argument("light volume build: photons to trace must be at least 1, got " + std::to_string(photons));
  State& s = *s_;
  s.check_whole();
  const auto start = std::chrono::steady_clock::now();
  const std::int64_t end = s.traced + std::min(photons, s.settings.photons - s.traced);
  s.broken = true;
  s.tallies->trace(s.traced, end, s.grid, s.g, s.media, s.similar, s.rect, s.settings, s.handover, *s.arena,
                   current_stop_token());
  s.broken = false;
  s.traced = end;
  s.seconds += seconds_since(start);
  return s.traced;
}

LightVolume LightVolumeBuild::volume() { return make_volume(false); }

LightVolume LightVolumeBuild::make_volume(bool consume) {
  State& s = *s_;
  s.check_whole();
  if (s.traced < 1) throw std::logic_error("light volume build: no photon traced yet");
  const auto start = std::chrono::steady_clock::now();
  const std::stop_token stop = current_stop_token();
  const CellGrid& g = s.g;
  LightVolume v = s.grid;
  v.photons = s.traced;
  const Tallies tallies = s.tallies->sums(consume, stop);
  // Track length per volume (eq. MS-2): phi = (E A / N) sum(w l) / V, per unit irradiance E.
  const double per_photon = s.rect.area_m2() / static_cast<double>(s.traced) / (v.cell_m.x * v.cell_m.y * v.cell_m.z);
  // The stages after the photons take up to tenths of a second each on a large grid: a poll
  // between them (cancel.hpp).
  throw_if_stopped(stop);
  CellValues values = cell_values(g, tallies.sum, s.coverage.covered, per_photon * tallies.quantum);
  throw_if_stopped(stop);
  if (s.handover.on()) {
    // Source per unit volume: q = (E A / N) sum(w) / V, per unit irradiance E.
    s.arena->execute([&] {
      add_diffused_light(g, v, s.medium, tallies.source, per_photon * kSourceQuantum, s.coverage, values, stop);
    });
  }
  clamp_spikes(g, values);
  throw_if_stopped(stop);
  smooth_anisotropy(g, values);
  throw_if_stopped(stop);
  std::vector<float> fit = linear_fits(g, values, s.coverage);
  throw_if_stopped(stop);
  fill_empty_rings(g, values, fit);
  throw_if_stopped(stop);
  pack_light_volume(values, std::move(fit), s.settings.fits, s.rect.l, v);
  s.seconds += seconds_since(start);
  v.build_seconds = s.seconds;
  return v;
}

LightVolume build_light_volume(const std::vector<CloudVolume>& clouds, const Light& light,
                               const LightVolumeSettings& settings) {
  LightVolumeBuild build(clouds, light, settings);
  build.trace(settings.photons);
  return build.make_volume(true);
}

}  // namespace nimbus::render

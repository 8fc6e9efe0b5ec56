// The shipped presets, told apart by measurement rather than by eye: each
// preset is generated (at 1.5 times its voxel size, to keep the suite fast) and its density is
// measured: the altitude range (1st to 99th percentile of density-weighted z), the horizontal
// extent per altitude band, the share of empty columns in a layer, the decay with height and
// with distance from an axis. The genus assertions compare those numbers, so swapping two
// presets (say stratus for stratocumulus, or humilis for congestus) makes a test fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus::volume {
namespace {

constexpr double kCoarsen = 1.5;      // voxel size used here, relative to the preset's own
constexpr float kThreshold = 1e-3f;   // densities at or below this count as "no cloud"

// A preset's density as a list of voxels (world positions in metres, z up).
struct Voxel {
  double x, y, z;
  float d;
};

struct Sample {
  CloudParams params;
  double voxel_size = 0.0;         // the preset's default
  double used_voxel_size = 0.0;    // voxel_size * kCoarsen
  openvdb::FloatGrid::Ptr grid;
  std::vector<Voxel> voxels;       // active voxels with density > kThreshold
  GenerateStats stats;
};

openvdb::FloatGrid::Ptr generate(const CloudParams& p, double voxel_size, GenerateStats* stats = nullptr) {
  GenerateOptions o;
  o.voxel_size = voxel_size;
  return generate_density(p, o, stats);
}

// Each preset is generated once per test run.
const Sample& sample(const std::string& name) {
  static std::map<std::string, Sample> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  Sample s;
  const nlohmann::json doc = load_preset(name);
  s.params = cloud_from_json(doc.at("cloud"), name);
  s.voxel_size = doc.at("voxel_size").get<double>();
  s.used_voxel_size = s.voxel_size * kCoarsen;
  s.grid = generate(s.params, s.used_voxel_size, &s.stats);
  for (auto v = s.grid->cbeginValueOn(); v; ++v) {
    if (!(*v > kThreshold)) continue;
    const openvdb::Vec3d w = s.grid->indexToWorld(v.getCoord());
    s.voxels.push_back({w.x(), w.y(), w.z(), *v});
  }
  return cache.emplace(name, std::move(s)).first->second;
}

// The measured numbers, printed so that a preset can be retuned against the assertions.
void report(const char* what, double value) { std::printf("  [measured] %-58s %12.4g\n", what, value); }

// The q-quantile (0..1) of `value` over the voxels, each weighted by its density.
template <class F>
double weighted_quantile(const std::vector<Voxel>& vs, F value, double q) {
  std::vector<std::pair<double, double>> vw;
  vw.reserve(vs.size());
  double total = 0.0;
  for (const Voxel& v : vs) {
    vw.push_back({value(v), v.d});
    total += v.d;
  }
  if (vw.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(vw.begin(), vw.end());
  double acc = 0.0;
  for (const auto& [x, w] : vw) {
    acc += w;
    if (acc >= q * total) return x;
  }
  return vw.back().first;
}

struct Range {
  double lo, hi;
  double size() const { return hi - lo; }
};

// Where the density lies along an axis: its 1st to 99th density-weighted percentile.
template <class F>
Range extent(const std::vector<Voxel>& vs, F value) {
  return {weighted_quantile(vs, value, 0.01), weighted_quantile(vs, value, 0.99)};
}
Range altitude_range(const std::vector<Voxel>& vs) { return extent(vs, [](const Voxel& v) { return v.z; }); }
Range x_range(const std::vector<Voxel>& vs) { return extent(vs, [](const Voxel& v) { return v.x; }); }
Range y_range(const std::vector<Voxel>& vs) { return extent(vs, [](const Voxel& v) { return v.y; }); }

std::vector<Voxel> band(const std::vector<Voxel>& vs, double z_lo, double z_hi) {
  std::vector<Voxel> out;
  for (const Voxel& v : vs)
    if (v.z >= z_lo && v.z <= z_hi) out.push_back(v);
  return out;
}

// The cloud's width: the larger of its x and y extents (the smaller one for `narrow`).
double horizontal_extent(const std::vector<Voxel>& vs, bool narrow = false) {
  const double x = x_range(vs).size(), y = y_range(vs).size();
  return narrow ? std::min(x, y) : std::max(x, y);
}

// Horizontal extent of the density between the fractions `from` and `to` of its altitude range.
double extent_of_band(const std::vector<Voxel>& vs, double from, double to) {
  const Range z = altitude_range(vs);
  return horizontal_extent(band(vs, z.lo + from * z.size(), z.lo + to * z.size()));
}

double height_over_width(const std::vector<Voxel>& vs) {
  return altitude_range(vs).size() / horizontal_extent(vs);
}

double mean_density(const std::vector<Voxel>& vs) {
  double sum = 0.0;
  for (const Voxel& v : vs) sum += v.d;
  return vs.empty() ? 0.0 : sum / double(vs.size());
}

double total_density(const std::vector<Voxel>& vs) {
  double sum = 0.0;
  for (const Voxel& v : vs) sum += v.d;
  return sum;
}

// A layer's middle horizontal slice (the middle third of its altitude range), over the inner
// 60 % of its horizontal extent (away from the faded rim): the share of columns in which no
// voxel of the slice holds cloud (gaps the light shines through), and the share of the slice's
// voxels that hold cloud (the coverage fraction).
struct LayerSlice {
  double empty_columns = 0.0;
  double coverage = 0.0;
};

LayerSlice middle_slice(const Sample& s) {
  const std::vector<Voxel>& vs = s.voxels;
  const Range z = altitude_range(vs), x = x_range(vs), y = y_range(vs);
  const double vsz = s.used_voxel_size;
  const auto idx = [vsz](double w) { return int(std::lround(w / vsz)); };
  const int x0 = idx(x.lo + 0.2 * x.size()), x1 = idx(x.hi - 0.2 * x.size());
  const int y0 = idx(y.lo + 0.2 * y.size()), y1 = idx(y.hi - 0.2 * y.size());
  const int z0 = idx(z.lo + z.size() / 3), z1 = idx(z.hi - z.size() / 3);
  const auto acc = s.grid->getConstAccessor();
  int64_t columns = 0, empty = 0, voxels = 0, full = 0;
  for (int i = x0; i <= x1; ++i)
    for (int j = y0; j <= y1; ++j) {
      bool any = false;
      for (int k = z0; k <= z1; ++k) {
        const bool cloud = acc.getValue(openvdb::Coord(i, j, k)) > kThreshold;
        any |= cloud;
        full += cloud;
        ++voxels;
      }
      ++columns;
      empty += !any;
    }
  return {double(empty) / double(columns), double(full) / double(voxels)};
}

// Mean length (voxels) of the runs of cloudy voxels along an axis (0: x, 1: y, 2: z): the
// cloudy voxels over the voxels that start a run.
double mean_run(const Sample& s, int axis) {
  const auto acc = s.grid->getConstAccessor();
  int64_t cloudy = 0, starts = 0;
  for (auto v = s.grid->cbeginValueOn(); v; ++v) {
    if (!(*v > kThreshold)) continue;
    ++cloudy;
    openvdb::Coord prev = v.getCoord();
    prev[axis] -= 1;
    starts += !(acc.getValue(prev) > kThreshold);
  }
  return starts ? double(cloudy) / double(starts) : 0.0;
}

const std::vector<std::string> kClouds = {
    "cumulus-humilis", "cumulus-mediocris", "cumulus-congestus", "cumulonimbus-capillatus-incus",
    "stratocumulus-stratiformis-perlucidus", "altocumulus-lenticularis", "cirrus-fibratus", "stratus"};
const std::vector<std::string> kGases = {"steam", "smoke"};

TEST(VolumeGenera, EveryGenusOfTheIssueShips) {
  std::vector<std::string> shipped;
  for (const auto& p : list_presets()) shipped.push_back(p.name);
  for (const auto& list : {kClouds, kGases})
    for (const std::string& name : list)
      EXPECT_NE(std::find(shipped.begin(), shipped.end(), name), shipped.end()) << name << " is not shipped";
}

TEST(VolumeGenera, EveryPresetIsFiniteNonNegativeAndAtItsVoxelSizeResolvedBy100To250Voxels) {
  for (const auto& info : list_presets()) {
    const Sample& s = sample(info.name);
    ASSERT_GT(s.stats.active_voxels, 1000) << info.name;
    for (auto v = s.grid->cbeginValueOn(); v; ++v) {
      ASSERT_TRUE(std::isfinite(*v)) << info.name;
      ASSERT_GT(*v, 0.0f) << info.name << ": active voxels hold density > 0";
    }
    // Across the largest side of the active box: about 100 to 250 voxels at the preset's
    // own voxel size (kCoarsen times fewer here).
    const openvdb::Coord dim = s.grid->evalActiveVoxelDim();
    const double across = kCoarsen * double(std::max({dim.x(), dim.y(), dim.z()}));
    if (s.params.field || info.name.ends_with("-field")) {
      // A field spans kilometres of many clouds: 300 to 1000 voxels across the area (its
      // largest clouds, 2.5 km, get about 125).
      EXPECT_GE(across, 300.0) << info.name << ": voxel_size is too coarse for the field's clouds";
      EXPECT_LE(across, 1000.0) << info.name << ": voxel_size is too fine for a field (slow, large files)";
      continue;
    }
    EXPECT_GE(across, 90.0) << info.name << ": voxel_size is too coarse for the cloud";
    EXPECT_LE(across, 270.0) << info.name << ": voxel_size is too fine (slow, large files)";
  }
}

TEST(VolumeGenera, EveryPresetRegeneratesBitIdenticallyAndTheSeedMatters) {
  for (const auto& info : list_presets()) {
    const Sample& s = sample(info.name);
    const auto again = generate(s.params, s.used_voxel_size);
    ASSERT_EQ(again->activeVoxelCount(), s.grid->activeVoxelCount()) << info.name;
    const auto acc = again->getConstAccessor();
    int64_t differ = 0;
    for (auto v = s.grid->cbeginValueOn(); v; ++v) {
      const float w = acc.getValue(v.getCoord());
      differ += std::memcmp(&w, &*v, sizeof(float)) != 0 || !acc.isValueOn(v.getCoord());
    }
    EXPECT_EQ(differ, 0) << info.name;
    // The check can fail: another seed gives another cloud.
    CloudParams other = s.params;
    other.seed += 1;
    const auto moved = generate(other, s.used_voxel_size);
    const auto macc = moved->getConstAccessor();
    int64_t changed = 0;
    for (auto v = s.grid->cbeginValueOn(); v; ++v) changed += macc.getValue(v.getCoord()) != *v;
    EXPECT_GT(changed, s.grid->activeVoxelCount() / 4) << info.name;
  }
}

// Low, middle and high clouds (the cloud families of Hoffmann 2007) sit at their altitudes.
TEST(VolumeGenera, CloudFamiliesSitAtTheirAltitudes) {
  for (const char* low : {"cumulus-humilis", "cumulus-mediocris", "cumulus-congestus",
                          "cumulonimbus-capillatus-incus", "stratocumulus-stratiformis-perlucidus", "stratus"}) {
    const Range z = altitude_range(sample(low).voxels);
    EXPECT_GT(z.lo, 300.0) << low;
    EXPECT_LT(z.lo, 2000.0) << low << ": base of a low (or towering) cloud";
  }
  const Range ac = altitude_range(sample("altocumulus-lenticularis").voxels);
  EXPECT_GT(ac.lo, 2000.0);
  EXPECT_LT(ac.hi, 7000.0);
  const Range ci = altitude_range(sample("cirrus-fibratus").voxels);
  EXPECT_GT(ci.lo, 6000.0) << "cirrus is a high cloud";
  EXPECT_LT(ci.hi, 12000.0);
}

TEST(VolumeGenera, CumulusSpeciesGrowFromWiderThanTallToTallerThanWide) {
  const auto& hum = sample("cumulus-humilis").voxels;
  const auto& med = sample("cumulus-mediocris").voxels;
  const auto& con = sample("cumulus-congestus").voxels;
  const double a_hum = height_over_width(hum), a_med = height_over_width(med), a_con = height_over_width(con);
  report("humilis height / width", a_hum);
  report("mediocris height / width", a_med);
  report("congestus height / width", a_con);
  report("congestus height (m)", altitude_range(con).size());
  report("mediocris height (m)", altitude_range(med).size());
  report("humilis height (m)", altitude_range(hum).size());
  EXPECT_LT(a_hum, 0.6) << "humilis: clearly wider than tall";
  EXPECT_GT(a_med, 0.6) << "mediocris: about as tall as wide";
  EXPECT_LT(a_med, 1.5) << "mediocris: about as tall as wide";
  EXPECT_GT(a_con, 1.5) << "congestus: taller than wide";
  EXPECT_LT(a_hum, a_med);
  EXPECT_LT(a_med, a_con);
  EXPECT_GT(altitude_range(con).size(), 2.0 * altitude_range(med).size()) << "congestus towers over mediocris";
  EXPECT_GT(altitude_range(med).size(), altitude_range(hum).size());
}

TEST(VolumeGenera, CumulonimbusAnvilIsWiderThanItsBaseAndTheCloudSpansTheTroposphere) {
  const auto& cb = sample("cumulonimbus-capillatus-incus").voxels;
  const Range z = altitude_range(cb);
  report("cumulonimbus altitude range (m)", z.size());
  EXPECT_GT(z.size(), 6000.0) << "a cumulonimbus reaches from a low base to the tropopause";
  EXPECT_GT(z.hi, 9000.0);
  const double bottom = extent_of_band(cb, 0.0, 0.15), top = extent_of_band(cb, 0.85, 1.0);
  report("cumulonimbus width of the top 15 % (anvil, m)", top);
  report("cumulonimbus width of the bottom 15 % (base, m)", bottom);
  EXPECT_GT(top, 2.0 * bottom) << "the anvil (top 15 %) is far wider than the base (bottom 15 %)";
  // The anvil is sheared downwind (+x, the wind's direction): its centre lies downwind of the base.
  const auto mid_x = [](const std::vector<Voxel>& vs) { return weighted_quantile(vs, [](const Voxel& v) { return v.x; }, 0.5); };
  const auto top_band = band(cb, z.lo + 0.85 * z.size(), z.hi), bottom_band = band(cb, z.lo, z.lo + 0.15 * z.size());
  report("cumulonimbus anvil shift downwind (m)", mid_x(top_band) - mid_x(bottom_band));
  EXPECT_GT(mid_x(top_band) - mid_x(bottom_band), 2000.0);
  EXPECT_GT(sample("cumulonimbus-capillatus-incus").params.wind.x, 0.0);
  // A cumulus has no anvil: the same measure says so.
  const auto& med = sample("cumulus-mediocris").voxels;
  report("mediocris width top 15 % / bottom 15 %", extent_of_band(med, 0.85, 1.0) / extent_of_band(med, 0.0, 0.15));
  EXPECT_LT(extent_of_band(med, 0.85, 1.0), 2.0 * extent_of_band(med, 0.0, 0.15));
}

TEST(VolumeGenera, StratocumulusIsABrokenLayerAndStratusAClosedOne) {
  const Sample& sc = sample("stratocumulus-stratiformis-perlucidus");
  const Sample& st = sample("stratus");
  for (const Sample* s : {&sc, &st}) {
    const double thickness = altitude_range(s->voxels).size();
    report(s == &sc ? "stratocumulus thickness / width" : "stratus thickness / width",
           thickness / horizontal_extent(s->voxels, true));
    EXPECT_LT(thickness, horizontal_extent(s->voxels, true) / 5.0) << "a layer: much wider than thick";
    EXPECT_LT(thickness, 700.0);
  }
  const LayerSlice a = middle_slice(sc), b = middle_slice(st);
  report("stratocumulus empty columns, middle slice", a.empty_columns);
  report("stratus empty columns, middle slice", b.empty_columns);
  report("stratocumulus coverage, middle slice", a.coverage);
  report("stratus coverage, middle slice", b.coverage);
  EXPECT_GT(a.empty_columns, 0.10) << "perlucidus: gaps the light shines through";
  EXPECT_LT(a.empty_columns, 0.70) << "still a layer, not scattered cloudlets";
  EXPECT_LT(b.empty_columns, 0.05) << "stratus: no gaps";
  EXPECT_LT(a.coverage, b.coverage);
  EXPECT_GT(b.coverage, 0.9);
  // Stratus is grey and uniform: its densities scatter little around their mean.
  double m = mean_density(st.voxels), var = 0.0;
  for (const Voxel& v : st.voxels) var += (v.d - m) * (v.d - m);
  const double cv_st = std::sqrt(var / double(st.voxels.size())) / m;
  m = mean_density(sc.voxels);
  var = 0.0;
  for (const Voxel& v : sc.voxels) var += (v.d - m) * (v.d - m);
  const double cv_sc = std::sqrt(var / double(sc.voxels.size())) / m;
  report("stratus density sd / mean", cv_st);
  report("stratocumulus density sd / mean", cv_sc);
  EXPECT_LT(cv_st, cv_sc) << "stratus is more uniform than stratocumulus";
}

TEST(VolumeGenera, LenticularisIsALensAtLeastFourTimesWiderThanThick) {
  const auto& ac = sample("altocumulus-lenticularis").voxels;
  const double thick = altitude_range(ac).size();
  report("lenticularis width / thickness (narrow side)", horizontal_extent(ac, true) / thick);
  report("lenticularis width / thickness (long side)", horizontal_extent(ac) / thick);
  EXPECT_GE(horizontal_extent(ac, true) / thick, 4.0) << "in every horizontal direction";
  // A lens: thickest near the middle, thinning to the rim. Per column, the cloud's thickness
  // (cloudy voxels times the voxel size), near the centre (inner quarter of the extents) and
  // near the rim (beyond 90 % of the extents, elliptic distance).
  const Sample& s = sample("altocumulus-lenticularis");
  const Range x = x_range(ac), y = y_range(ac);
  const double cx = 0.5 * (x.lo + x.hi), cy = 0.5 * (y.lo + y.hi), rx = 0.5 * x.size(), ry = 0.5 * y.size();
  std::map<std::pair<int, int>, int> column;
  for (const Voxel& v : ac)
    ++column[{int(std::lround(v.x / s.used_voxel_size)), int(std::lround(v.y / s.used_voxel_size))}];
  double centre = 0.0, rim = 0.0;
  int n_centre = 0, n_rim = 0;
  for (const auto& [ij, count] : column) {
    const double u = std::hypot((ij.first * s.used_voxel_size - cx) / rx, (ij.second * s.used_voxel_size - cy) / ry);
    if (u < 0.25) {
      centre += count;
      ++n_centre;
    } else if (u > 0.9) {
      rim += count;
      ++n_rim;
    }
  }
  ASSERT_GT(n_centre, 0);
  ASSERT_GT(n_rim, 0);
  report("lenticularis mean column thickness centre / rim", (centre / n_centre) / (rim / n_rim));
  EXPECT_GT(centre / n_centre, 1.8 * rim / n_rim);
}

TEST(VolumeGenera, CirrusIsHighFaintAndStreakedAlongTheWind) {
  const Sample& ci = sample("cirrus-fibratus");
  EXPECT_GT(altitude_range(ci.voxels).lo, 6000.0);
  const double cu = mean_density(sample("cumulus-mediocris").voxels);
  report("cirrus lowest altitude (m)", altitude_range(ci.voxels).lo);
  report("cirrus mean density", mean_density(ci.voxels));
  report("mediocris mean density", cu);
  report("cirrus mean run along x / along y", mean_run(ci, 0) / mean_run(ci, 1));
  report("mediocris mean run along x / along y", mean_run(sample("cumulus-mediocris"), 0) / mean_run(sample("cumulus-mediocris"), 1));
  EXPECT_LT(mean_density(ci.voxels), 0.5 * cu) << "cirrus is much fainter than cumulus";
  // Streaks: cloudy runs of voxels are long along the wind (x) and short across it (y); a
  // cumulus has no such direction.
  const glm::dvec3 wind = ci.params.wind;
  EXPECT_GT(std::fabs(wind.x), 3.0 * std::fabs(wind.y)) << "the streaks lie along x, as the wind";
  EXPECT_GT(mean_run(ci, 0), 2.5 * mean_run(ci, 1)) << "fibres along the wind";
  const Sample& cu_s = sample("cumulus-mediocris");
  EXPECT_LT(mean_run(cu_s, 0), 1.5 * mean_run(cu_s, 1)) << "the measure can tell streaks from heaps";
}

TEST(VolumeGenera, SteamFadesWithHeightAndWithDistanceFromTheAxis) {
  const auto& steam = sample("steam").voxels;
  const Range z = altitude_range(steam);
  EXPECT_LT(z.lo, 0.02) << "steam starts at the cup (z = 0)";
  EXPECT_GT(z.hi, 0.15);
  EXPECT_LT(z.hi, 0.4);
  // Mean density over the same volume of each third: the total density of the thirds.
  const double bottom = total_density(band(steam, z.lo, z.lo + z.size() / 3));
  const double top = total_density(band(steam, z.hi - z.size() / 3, z.hi));
  report("steam density top third / bottom third", top / bottom);
  EXPECT_LT(top, bottom / 3.0) << "steam thins out as it rises";
  // Near the axis (r < 2 cm) the steam is denser than in the ring 4 to 6 cm out, per volume.
  double inner = 0.0, outer = 0.0;
  for (const Voxel& v : steam) {
    const double r = std::hypot(v.x, v.y);
    if (r < 0.02) inner += v.d;
    if (r > 0.04 && r < 0.06) outer += v.d;
  }
  const double inner_area = 0.02 * 0.02, outer_area = 0.06 * 0.06 - 0.04 * 0.04;
  report("steam density per area, r < 2 cm / 4-6 cm", (inner / inner_area) / (outer / outer_area));
  EXPECT_GT(inner / inner_area, 3.0 * outer / outer_area) << "steam thins out away from the centre";
}

TEST(VolumeGenera, SmokeRisesSpreadsDriftsAndCoolsWithHeight) {
  const Sample& s = sample("smoke");
  const auto& smoke = s.voxels;
  const Range z = altitude_range(smoke);
  EXPECT_GT(z.size(), 10.0);
  report("smoke width top 20 % / bottom 20 %", extent_of_band(smoke, 0.8, 1.0) / extent_of_band(smoke, 0.0, 0.2));
  EXPECT_GT(extent_of_band(smoke, 0.8, 1.0), 2.0 * extent_of_band(smoke, 0.0, 0.2)) << "the plume spreads";
  const auto mid_x = [](const std::vector<Voxel>& vs) { return weighted_quantile(vs, [](const Voxel& v) { return v.x; }, 0.5); };
  const double drift = mid_x(band(smoke, z.hi - z.size() / 3, z.hi)) - mid_x(band(smoke, z.lo, z.lo + z.size() / 3));
  report("smoke drift downwind, top third - bottom third (m)", drift);
  EXPECT_GT(drift, 5.0) << "the plume drifts downwind (+x)";
  const auto temp = generate_temperature(s.params, *s.grid);
  ASSERT_TRUE(temp) << "smoke has a temperature grid";
  EXPECT_EQ(temp->activeVoxelCount(), s.grid->activeVoxelCount());
  EXPECT_EQ(temp->transform(), s.grid->transform());
  // Temperature falls with height: never rises from one voxel to a higher one, and the top
  // third is clearly cooler than the bottom third.
  std::vector<std::pair<double, float>> zt;
  for (auto v = temp->cbeginValueOn(); v; ++v) zt.push_back({temp->indexToWorld(v.getCoord()).z(), *v});
  std::sort(zt.begin(), zt.end());
  double bottom = 0.0, top = 0.0;
  int nb = 0, nt = 0;
  for (size_t i = 0; i < zt.size(); ++i) {
    ASSERT_TRUE(zt[i].second >= 0.0f && zt[i].second <= 1.0f);
    if (i > 0 && zt[i].first > zt[i - 1].first) {
      ASSERT_LE(zt[i].second, zt[i - 1].second) << "at z = " << zt[i].first;
    }
    if (zt[i].first < z.lo + z.size() / 3) {
      bottom += zt[i].second;
      ++nb;
    }
    if (zt[i].first > z.hi - z.size() / 3) {
      top += zt[i].second;
      ++nt;
    }
  }
  ASSERT_GT(nb, 0);
  ASSERT_GT(nt, 0);
  report("smoke mean temperature, bottom third", bottom / nb);
  report("smoke mean temperature, top third", top / nt);
  EXPECT_LT(top / nt, bottom / nb - 0.3);
  // Steam is hot too; clouds carry no temperature grid.
  EXPECT_TRUE(generate_temperature(sample("steam").params, *sample("steam").grid));
  for (const std::string& cloud : kClouds)
    EXPECT_FALSE(generate_temperature(sample(cloud).params, *sample(cloud).grid)) << cloud;
}

}  // namespace
}  // namespace nimbus::volume

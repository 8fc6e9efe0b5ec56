// The cloud density field (see cloud_model.hpp for the equations).
#include "nimbus/volume/cloud_model.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "nimbus/noise/batch.hpp"
#include "nimbus/noise/footprint.hpp"

namespace nimbus::volume {
namespace {

void need(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A periodic model's noise: a whole number of cycles per period on x and y (at least one), the
// frequency moved to the nearest such (from the x period; the y period must then hold a whole
// number too), and the lattice period set; z stays aperiodic.
void make_periodic(double* frequency, std::array<int32_t, 3>* period, const std::optional<PeriodicTile>& tile) {
  if (!tile) return;
  const double cx = std::max(1.0, std::round(tile->size_m.x * *frequency));
  const double f = cx / tile->size_m.x, cy = tile->size_m.y * f;
  need(std::fabs(cy - std::round(cy)) <= 1e-6 * cy && cy >= 0.5,
       "period: the x and y periods admit no common noise frequency near " + std::to_string(*frequency) +
           " cycles per metre (use equal periods, or periods in a ratio of whole numbers)");
  need(cx <= double(1 << 30) && cy <= double(1 << 30), "period: too many noise cycles per period (at most 2^30)");
  *frequency = f;
  *period = {int32_t(cx), int32_t(std::round(cy)), 0};
}

std::unique_ptr<noise::NoiseField> make_field(noise::Kind kind, noise::Fractal fractal, int octaves,
                                              double frequency, double lacunarity, double gain,
                                              uint32_t seed, double evolution, double t,
                                              double voxel_size, const std::optional<PeriodicTile>& tile) {
  noise::NoiseParams n;
  make_periodic(&frequency, &n.period, tile);
  n.kind = kind;
  n.fractal = fractal;
  n.octaves = octaves;
  n.frequency = frequency;
  n.lacunarity = lacunarity;
  n.gain = gain;
  n.seed = seed;
  if (evolution != 0.0) n.time = evolution * t;
  // Model only what the voxels can show: no octave above their Nyquist limit.
  return std::make_unique<noise::NoiseField>(noise::limit_octaves(n, voxel_size));
}

}  // namespace

std::optional<PeriodicTile> periodic_tile(const CloudParams& p) {
  if (p.field && p.field->periodic) return PeriodicTile{p.field->center_m - 0.5 * p.field->size_m, p.field->size_m};
  if (p.period_m.x > 0.0 && p.period_m.y > 0.0) return PeriodicTile{-0.5 * p.period_m, p.period_m};
  return std::nullopt;
}

void validate(const CloudParams& p) {
  need(!p.shapes.empty() || p.field, "shapes: at least one shape (or a field) is needed");
  if (p.field) validate(*p.field);
  for (size_t i = 0; i < p.shapes.size(); ++i) validate(p.shapes[i], "shapes[" + std::to_string(i) + "]");
  need(std::isfinite(p.base_altitude), "base_altitude must be finite (metres)");
  need(std::isfinite(p.base_softness) && p.base_softness > 0, "base_softness must be finite and > 0 (metres)");
  need(!std::isnan(p.ceiling_altitude) && p.ceiling_altitude > -1e29, "ceiling_altitude must be a number (metres)");
  need(std::isfinite(p.ceiling_softness) && p.ceiling_softness > 0, "ceiling_softness must be finite and > 0 (metres)");
  need(std::isfinite(p.flat_layer) && p.flat_layer >= 0, "flat_layer must be finite and >= 0 (metres)");
  need(std::isfinite(p.frequency) && p.frequency > 0, "frequency must be finite and > 0 (cycles per metre)");
  need(p.octaves >= 1 && p.octaves <= noise::kMaxOctaves, "octaves must be in [1, 24]");
  need(std::isfinite(p.lacunarity) && p.lacunarity > 1 && p.lacunarity <= 16, "lacunarity must be in (1, 16]");
  need(std::isfinite(p.gain) && p.gain > 0 && p.gain <= 1, "gain must be in (0, 1]");
  need(p.coverage >= 0 && p.coverage <= 1, "coverage must be in [0, 1]");
  need(std::isfinite(p.billow) && p.billow >= 0, "billow must be finite and >= 0");
  need(p.erosion >= 0 && p.erosion <= 1, "erosion must be in [0, 1]");
  need(std::isfinite(p.erosion_frequency) && p.erosion_frequency > 0, "erosion_frequency must be finite and > 0");
  need(p.furrows >= 0 && p.furrows <= 1, "furrows must be in [0, 1]");
  need(std::isfinite(p.furrow_frequency) && p.furrow_frequency > 0, "furrow_frequency must be finite and > 0");
  need(std::isfinite(p.displacement) && p.displacement >= 0, "displacement must be finite and >= 0 (metres)");
  need(std::isfinite(p.displacement_frequency) && p.displacement_frequency > 0,
       "displacement_frequency must be finite and > 0");
  need(std::isfinite(p.gas.max_density) && p.gas.max_density >= 0, "density must be finite and >= 0");
  need(std::isfinite(p.gas.exponent) && p.gas.exponent > 0 && p.gas.exponent <= 16, "exponent must be in (0, 16]");
  need(finite3(p.wind), "wind must be finite (metres per second)");
  need(std::isfinite(p.evolution), "evolution must be finite");
  need(p.cauliflower >= 0 && p.cauliflower <= 1, "cauliflower must be in [0, 1]");
  need(std::isfinite(p.cauliflower_frequency) && p.cauliflower_frequency > 0, "cauliflower_frequency must be finite and > 0");
  need(std::isfinite(p.stretch) && p.stretch >= 1 && p.stretch <= 64, "stretch must be in [1, 64]");
  need(!std::isnan(p.stretch_altitude), "stretch_altitude must be a number (metres)");
  need(std::isfinite(p.stretch_direction.x) && std::isfinite(p.stretch_direction.y) &&
           std::hypot(p.stretch_direction.x, p.stretch_direction.y) > 1e-12,
       "stretch_direction must be finite and non-zero (x, y)");
  need(std::isfinite(p.shear.x) && std::isfinite(p.shear.y) && std::fabs(p.shear.x) <= 10 && std::fabs(p.shear.y) <= 10,
       "shear must be finite and within [-10, 10] (metres per metre)");
  need(std::isfinite(p.temperature_base), "temperature_base must be finite (metres)");
  need(std::isfinite(p.temperature_height) && p.temperature_height >= 0,
       "temperature_height must be finite and >= 0 (metres; 0: no temperature grid)");
  need(std::isfinite(p.period_m.x) && std::isfinite(p.period_m.y) && p.period_m.x >= 0 && p.period_m.y >= 0 &&
           p.period_m.x <= 1e6 && p.period_m.y <= 1e6 && (p.period_m.x > 0) == (p.period_m.y > 0),
       "period must be [0, 0] or positive on both axes, at most 1e6 (metres)");
  if (p.field && p.field->periodic && p.period_m.x > 0)
    need(p.period_m == p.field->size_m, "period must equal field.size when field.periodic is true (or be [0, 0])");
  if (periodic_tile(p)) {
    need(p.stretch == 1.0, "stretch: fibres (stretch > 1) are not periodic; set stretch 1, or make the field not periodic");
    need(p.noise != noise::Kind::Wavelet,
         "noise: wavelet noise is periodic only on all three axes; a periodic field needs value, gradient or worley");
    need(p.lacunarity == std::floor(p.lacunarity), "lacunarity must be a whole number in a periodic field");
  }
  const auto& e = p.coverage_map_extent;
  need(std::isfinite(e[0]) && std::isfinite(e[1]) && std::isfinite(e[2]) && std::isfinite(e[3]) &&
           ((e[0] == 0 && e[1] == 0 && e[2] == 0 && e[3] == 0) || (e[2] > e[0] && e[3] > e[1])),
       "coverage_map_extent must be [west, south, east, north] with east > west and north > south (metres), or all 0");
}

CloudModel::CloudModel(const CloudParams& params, double voxel_size, double time_seconds)
    : params_(params), time_(time_seconds) {
  validate(params_);
  need(std::isfinite(voxel_size) && voxel_size > 0, "voxel size must be finite and > 0 (metres)");
  need(std::isfinite(time_seconds), "time must be finite (seconds)");
  const CloudParams& p = params_;
  tile_ = periodic_tile(p);
  if (p.coverage_image || !p.coverage_map.empty()) make_map();
  shapes_ = p.shapes;
  if (p.field) {
    const std::vector<Shape> f = field_shapes(*p.field, p.base_altitude > -1e29 ? p.base_altitude : 0.0, map_.get());
    shapes_.insert(shapes_.end(), f.begin(), f.end());
  }
  shear_base_ = p.base_altitude > -1e29 ? p.base_altitude : 0.0;
  for (Shape& s : shapes_)
    if (s.rooted) s.root_z = shear_base_;  // turrets stand on the base
  if (tile_) replicate_shapes();
  index_ = std::make_unique<ShapeIndex>(shapes_);
  for (const Shape& sh : shapes_) bound_shapes_.push_back(bound_shape(sh));
  fibre_dir_ = p.stretch_direction / std::hypot(p.stretch_direction.x, p.stretch_direction.y);
  if (p.cauliflower > 0) {
    noise::PerlinWorleyParams pw;
    pw.frequency = p.cauliflower_frequency;
    make_periodic(&pw.frequency, &pw.period, tile_);
    pw.seed = p.seed + 7;
    if (p.evolution != 0.0) pw.time = p.evolution * time_;
    pw.perlin_octaves = noise::octaves_for_footprint(noise::perlin_part(pw), voxel_size).octaves;
    pw.worley_octaves = noise::octaves_for_footprint(noise::worley_part(pw), voxel_size).octaves;
    cauli_ = std::make_unique<noise::PerlinWorleyField>(pw);
  }
  billow_ = make_field(p.noise, noise::Fractal::Fbm, p.octaves, p.frequency, p.lacunarity, p.gain,
                       p.seed, p.evolution, time_, voxel_size, tile_);
  if (p.erosion > 0)
    detail_ = make_field(p.noise, noise::Fractal::Turbulence, 3, p.erosion_frequency, 2.0, 0.5,
                         p.seed + 1, p.evolution, time_, voxel_size, tile_);
  if (p.furrows > 0)
    furrow_ = make_field(p.noise, noise::Fractal::Ridged, 3, p.furrow_frequency, 2.0, 0.5, p.seed + 5,
                         p.evolution, time_, voxel_size, tile_);
  if (p.displacement > 0)
    for (int a = 0; a < 3; ++a)
      disp_[a] = make_field(noise::Kind::Gradient, noise::Fractal::Fbm, 3, p.displacement_frequency,
                            2.0, 0.5, p.seed + 2 + a, p.evolution, time_, voxel_size, tile_);
  threshold_ = 1.0 - p.coverage;
  mean_ = billow_->expected_mean();  // Worley noise is not centred
  inv_sd_ = 1.0 / billow_->expected_sd();
  min_useful_coverage_ = threshold_ / (1.0 + p.billow * std::max((1.0 - mean_) * inv_sd_, kBaseBillow));
  // The largest density the parameters can give, where coverage is 1 and the billow noise at the
  // top of its range (erosion, furrows and cauliflower only take away), must be a float: voxels
  // beyond it would overflow. The stored grids are floats, so refuse rather than saturate.
  const double f_max = p.gas.sine ? 1.0 : 1.0 + p.billow * (double(billow_->range().hi) - mean_) * inv_sd_ - threshold_;
  const double peak = std::pow(std::max(f_max, 0.0) * double(p.gas.max_density), double(p.gas.exponent));
  if (!(peak <= double(std::numeric_limits<float>::max()))) {
    std::ostringstream m;
    m << "density " << p.gas.max_density << " with exponent " << p.gas.exponent << " gives densities up to "
      << peak << ", beyond the float range (" << std::numeric_limits<float>::max() << ")";
    throw std::invalid_argument(m.str());
  }
}

int CloudModel::octaves_used() const { return billow_->data().octaves; }

void CloudModel::make_map() {
  const CloudParams& p = params_;
  std::shared_ptr<const CoverageImage> image = p.coverage_image ? p.coverage_image : read_coverage_png(p.coverage_map);
  const auto& e = p.coverage_map_extent;
  glm::dvec2 lo, size;
  if (e[2] > e[0]) {
    lo = {e[0], e[1]};
    size = {e[2] - e[0], e[3] - e[1]};
    if (tile_)
      need(std::fabs(lo.x - tile_->lo_m.x) <= 1e-9 * tile_->size_m.x && std::fabs(lo.y - tile_->lo_m.y) <= 1e-9 * tile_->size_m.y &&
               std::fabs(size.x - tile_->size_m.x) <= 1e-9 * tile_->size_m.x &&
               std::fabs(size.y - tile_->size_m.y) <= 1e-9 * tile_->size_m.y,
           "coverage_map_extent: a periodic field's map must span its tile (or leave the extent out)");
  } else if (p.field) {
    lo = p.field->center_m - 0.5 * p.field->size_m;
    size = p.field->size_m;
  } else if (tile_) {
    lo = tile_->lo_m;
    size = tile_->size_m;
  } else {
    need(!p.shapes.empty(), "coverage_map: no shapes to stretch the map over; give coverage_map_extent");
    Aabb b = shape_bounds(p.shapes[0]);
    for (const Shape& s : p.shapes) b = b.united(shape_bounds(s));
    lo = {b.lo.x, b.lo.y};
    size = {b.hi.x - b.lo.x, b.hi.y - b.lo.y};
  }
  map_ = std::make_unique<CoverageMap>(std::move(image), lo, size, tile_.has_value(), p.coverage_map_height);
}

void CloudModel::replicate_shapes() {
  const glm::dvec2 P = tile_->size_m, lo = tile_->lo_m, hi = lo + P;
  const double margin = params_.displacement + 1.0;  // the displacement's reach past an edge
  std::vector<Shape> out;
  for (size_t i = 0; i < shapes_.size(); ++i) {
    Shape s = shapes_[i];
    bool endless[2] = {false, false};
    for (int a = 0; a < 2; ++a) {
      if (s.kind == ShapeKind::Slab && 2.0 * s.size[a] >= P[a] * (1.0 - 1e-9)) {
        // A layer as wide as the period: endless along this axis. Centred on the tile and wide
        // enough that its horizontal falloff never reaches a point of the tile.
        need(s.roughness == 0.0, "period: a slab as wide as the period (shapes[" + std::to_string(i) +
                                     "]) must have roughness 0 (its outline noise is not periodic)");
        s.center[a] = lo[a] + 0.5 * P[a];
        s.size[a] = 0.5 * P[a] / std::max(1.0 - s.falloff, 1e-3) * 1.001;
        endless[a] = true;
      }
    }
    const Aabb b = shape_bounds(s);
    need((endless[0] || b.hi.x - b.lo.x < P.x) && (endless[1] || b.hi.y - b.lo.y < P.y),
         "period: a shape " + std::to_string(int(std::max(b.hi.x - b.lo.x, b.hi.y - b.lo.y))) +
             " m wide does not fit in the period (" + std::to_string(int(P.x)) + " x " + std::to_string(int(P.y)) +
             " m): lower max_diameter, or widen the field");
    // Moved by whole periods so that its box's centre lies in the tile (along the other axes).
    const glm::dvec2 c = 0.5 * (glm::dvec2(b.lo.x, b.lo.y) + glm::dvec2(b.hi.x, b.hi.y));
    const glm::dvec2 k = glm::floor((c - lo) / P);
    const glm::dvec3 shift(endless[0] ? 0.0 : -k.x * P.x, endless[1] ? 0.0 : -k.y * P.y, 0.0);
    s.center += shift;
    s.end += shift;
    for (int dy = endless[1] ? 0 : -1; dy <= (endless[1] ? 0 : 1); ++dy)
      for (int dx = endless[0] ? 0 : -1; dx <= (endless[0] ? 0 : 1); ++dx) {
        Shape r = s;
        const glm::dvec3 o(dx * P.x, dy * P.y, 0.0);
        r.center += o;
        r.end += o;
        const Aabb rb = shape_bounds(r);
        if (rb.hi.x > lo.x - margin && rb.lo.x < hi.x + margin && rb.hi.y > lo.y - margin && rb.lo.y < hi.y + margin)
          out.push_back(r);
      }
  }
  shapes_ = std::move(out);
}

glm::dvec3 CloudModel::wrapped(const glm::dvec3& q) const {
  if (!tile_) return q;
  const glm::dvec2 P = tile_->size_m, lo = tile_->lo_m;
  // 0 <= d < P gives d / P < 1 after rounding too, so the floor is 0 and q stays as it is: the
  // common case, without the divisions.
  const double dx = q.x - lo.x, dy = q.y - lo.y;
  const double x = dx >= 0.0 && dx < P.x ? q.x : q.x - P.x * std::floor(dx / P.x);
  const double y = dy >= 0.0 && dy < P.y ? q.y : q.y - P.y * std::floor(dy / P.y);
  return {x, y, q.z};
}

double CloudModel::map_at(const glm::dvec3& p) const {
  if (!map_) return 1.0;
  return map_->at({p.x - params_.wind.x * time_, p.y - params_.wind.y * time_});
}

glm::dvec3 CloudModel::sheared(const glm::dvec3& p) const {
  glm::dvec3 q = p - params_.wind * time_;
  q.x -= params_.shear.x * (q.z - shear_base_);
  q.y -= params_.shear.y * (q.z - shear_base_);
  return q;
}

glm::dvec3 CloudModel::noise_point(const glm::dvec3& q) const {
  if (params_.stretch == 1.0) return q;
  const double x = std::clamp((q.z - params_.stretch_altitude) / 200.0, 0.0, 1.0);
  const double w = x * x * (3.0 - 2.0 * x);
  const double squeeze = 1.0 - w * (1.0 - 1.0 / params_.stretch);  // 1 below, 1/stretch above
  const double along = q.x * fibre_dir_.x + q.y * fibre_dir_.y;
  return {q.x + (squeeze - 1.0) * along * fibre_dir_.x, q.y + (squeeze - 1.0) * along * fibre_dir_.y, q.z};
}

glm::dvec3 CloudModel::displacement(float x, float y, float z) const {
  // Each component is in [-1, 1], so the vector could reach sqrt(3) displacements; the far
  // test (far_points) bounds the reach by one, so a longer vector is shortened to that. None
  // is in practice: 3-octave fBm has a standard deviation near 0.12 per component.
  glm::dvec3 d(x, y, z);
  const double len2 = glm::dot(d, d);
  if (len2 > 1.0) d /= std::sqrt(len2);
  return params_.displacement * d;
}

glm::dvec3 CloudModel::moved(const glm::dvec3& p) const {
  glm::dvec3 q = sheared(p);
  if (disp_[0]) q += displacement(disp_[0]->eval(q.x, q.y, q.z), disp_[1]->eval(q.x, q.y, q.z), disp_[2]->eval(q.x, q.y, q.z));
  return q;
}

namespace {

double smoothstep01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// The ceiling's share at the undisplaced altitude z0: 1 below its soft layer, 0 above it.
double ceiling_factor(const CloudParams& p, double z0) {
  return z0 > p.ceiling_altitude - p.ceiling_softness ? smoothstep01((p.ceiling_altitude - z0) / p.ceiling_softness) : 1.0;
}

}  // namespace

double CloudModel::coverage_at(const glm::dvec3& q_in, double z0) const {
  const CloudParams& p = params_;
  const glm::dvec3 q = wrapped(q_in);
  const double ceiling = ceiling_factor(p, z0);
  double s = 0.0;
  index_->visit(q, [&](uint32_t i) {
    const double c = shape_coverage(shapes_[i], q);
    s = std::max(s, shapes_[i].overshoot ? c : c * ceiling);
  });
  if (s > 0.0 && z0 < p.base_altitude + p.base_softness) s *= smoothstep01((z0 - p.base_altitude) / p.base_softness);
  return s;
}

namespace {

// One point's shape whose coverage waits for its roughness noise, with the start of it.
struct CoverageEntry {
  uint32_t point, shape;
  CoverageStart start;
};

// Per-thread working memory of densities() and coverages(), kept from one leaf block to the
// next so that a block allocates nothing (a batch larger than kKeptPoints gives it back).
struct DensityScratch {
  std::vector<std::array<double, 3>> q, near, busy, bitten, noise_points;
  std::vector<double> z0, s;
  std::vector<uint8_t> far;
  std::vector<glm::dvec3> m, w;
  std::vector<uint32_t> near_shapes, where, which;
  std::vector<float> d[3], nb, nd, nr, nc, noise;
  std::vector<CoverageEntry> entries;
};
constexpr size_t kKeptPoints = 4096;

DensityScratch& density_scratch() {
  thread_local DensityScratch scratch;
  return scratch;
}

}  // namespace

void CloudModel::coverages(const std::vector<std::array<double, 3>>& q, const std::vector<double>& z0,
                           const std::vector<uint8_t>& skip, std::vector<double>& s) const {
  const CloudParams& p = params_;
  DensityScratch& t = density_scratch();
  // Each point's shapes: a coverage that needs no roughness noise is folded into the point's
  // at once (a zero one leaves it as it is); the others wait for their noise, evaluated in one
  // batch. s is a maximum, so the order does not change it.
  std::vector<CoverageEntry>& entries = t.entries;
  std::vector<std::array<double, 3>>& noise_points = t.noise_points;
  std::vector<glm::dvec3>& w = t.w;
  entries.clear();
  noise_points.clear();
  w.resize(q.size());
  s.assign(q.size(), 0.0);
  auto fold = [&](size_t i, uint32_t k, double c) {
    s[i] = std::max(s[i], shapes_[k].overshoot ? c : c * ceiling_factor(p, z0[i]));
  };
  for (size_t i = 0; i < q.size(); ++i) {
    if (skip[i]) continue;
    w[i] = wrapped(glm::dvec3(q[i][0], q[i][1], q[i][2]));
    index_->visit(w[i], [&](uint32_t k) {
      const CoverageStart start = coverage_start(shapes_[k], w[i]);
      if (start.zero) return;
      if (!start.needs_noise) {
        fold(i, k, coverage_finish(shapes_[k], w[i], start, 0.0f));
        return;
      }
      entries.push_back(CoverageEntry{static_cast<uint32_t>(i), k, start});
      noise_points.push_back(start.noise_point);
    });
  }
  std::vector<float>& noise = t.noise;
  noise.resize(noise_points.size());
  if (!noise_points.empty())
    noise::evaluate_points(shape_roughness_noise(), noise_points, noise, noise::BatchOptions{std::nullopt, false});
  for (size_t m = 0; m < entries.size(); ++m) {
    const CoverageEntry& e = entries[m];
    fold(e.point, e.shape, coverage_finish(shapes_[e.shape], w[e.point], e.start, noise[m]));
  }
  for (size_t i = 0; i < q.size(); ++i)
    if (!skip[i] && s[i] > 0.0 && z0[i] < p.base_altitude + p.base_softness)
      s[i] *= smoothstep01((z0[i] - p.base_altitude) / p.base_softness);
}

double CloudModel::calm(double z0) const {
  const CloudParams& p = params_;
  if (!(p.flat_layer > 0.0)) return 1.0;
  const double above_base = p.base_altitude > -1e29 ? (z0 - p.base_altitude) / p.flat_layer : 1.0;
  const double below_ceiling = p.ceiling_altitude < 1e29 ? (p.ceiling_altitude - z0) / p.flat_layer : 1.0;
  return smoothstep01(std::min(above_base, below_ceiling));
}

double CloudModel::unbitten(double s, double w, float billow_noise) const {
  const double z = w * (double(billow_noise) - mean_) * inv_sd_ + (1.0 - w) * kBaseBillow;
  return s * (1.0 + params_.billow * z) - threshold_;
}

float CloudModel::finish(double s, double w, float billow_noise, float detail, float furrow, float cauli) const {
  // eaten >= 0 (erosion, furrows, cauliflower in [0, 1]; turbulence and ridged sums >= 0;
  // Perlin-Worley in [0, 1]) and w >= 0, so f <= unbitten in floating point too.
  const double eaten = params_.erosion * double(detail) + params_.furrows * double(furrow) +
                       params_.cauliflower * (1.0 - double(cauli));
  const double f = unbitten(s, w, billow_noise) - w * eaten;
  return gas_density(static_cast<float>(f), params_.gas);
}

float CloudModel::density(const glm::dvec3& p) const {
  const double z0 = sheared(p).z;
  const glm::dvec3 q = moved(p);
  const double s = coverage_at(q, z0) * map_at(p);  // the map: 0 leaves no cloud
  if (!(s > min_useful_coverage_)) return 0.0f;
  const glm::dvec3 m = noise_point(q);
  const float n = billow_->eval(m.x, m.y, m.z);
  if (!(unbitten(s, calm(z0), n) > 0.0)) return 0.0f;  // nothing the other noises could leave
  const float d = detail_ ? detail_->eval(m.x, m.y, m.z) : 0.0f;
  const float r = furrow_ ? furrow_->eval(m.x, m.y, m.z) : 0.0f;
  const float c = cauli_ ? cauli_->eval(m.x, m.y, m.z) : 1.0f;
  return finish(s, calm(z0), n, d, r, c);
}

Aabb CloudModel::lean(double z_lo, double z_hi) const {
  // shear (z - base) over z in [z_lo, z_hi]: its least and greatest horizontal offsets.
  const double z0 = z_lo - shear_base_, z1 = z_hi - shear_base_;
  const glm::dvec2 a = params_.shear * z0, b = params_.shear * z1;
  return {glm::dvec3(std::min(a.x, b.x), std::min(a.y, b.y), 0.0), glm::dvec3(std::max(a.x, b.x), std::max(a.y, b.y), 0.0)};
}

Aabb CloudModel::world_box(const Aabb& b) const {
  // p = q0 + wind t + shear (q0.z - base): the lean spans the box's height.
  const Aabb l = lean(b.lo.z, b.hi.z);
  const glm::dvec3 shift = params_.wind * time_;
  return {b.lo + l.lo + shift, b.hi + l.hi + shift};
}

Aabb CloudModel::bounds() const {
  Aabb b = index_->bounds().expanded(params_.displacement);
  // Nothing below the base (coverage is 0 there, in q0): rooted shapes' undersides reach below it.
  if (params_.base_altitude > -1e29) b.lo.z = std::min(std::max(b.lo.z, params_.base_altitude), b.hi.z);
  Aabb w = world_box(b);
  if (tile_) {  // an endless field: one period, fixed in the world (the wind moves the clouds through it)
    w.lo.x = tile_->lo_m.x;
    w.lo.y = tile_->lo_m.y;
    w.hi.x = tile_->lo_m.x + tile_->size_m.x;
    w.hi.y = tile_->lo_m.y + tile_->size_m.y;
  }
  return w;
}

bool CloudModel::may_touch(const Aabb& w) const {
  // The world box in q0 coordinates (the inverse of world_box), grown by the displacement.
  const glm::dvec3 shift = params_.wind * time_;
  const Aabb l = lean(w.lo.z - shift.z, w.hi.z - shift.z);
  const Aabb q = Aabb{w.lo - shift - l.hi, w.hi - shift - l.lo}.expanded(params_.displacement);
  if (!tile_) return index_->any_overlaps(q);
  // Periodic: the box moved by whole periods into the tile, and its part past the tile's far
  // edge tested again one period back (the shapes are held in the tile and just across it).
  double xs[2][2], ys[2][2];
  auto wrap_range = [](double lo, double hi, double tlo, double P, double (*out)[2]) {
    if (hi - lo >= P) {
      out[0][0] = tlo - 1.0;
      out[0][1] = tlo + P + 1.0;
      return 1;
    }
    const double k = std::floor((lo - tlo) / P);
    lo -= k * P;
    hi -= k * P;
    out[0][0] = lo;
    out[0][1] = hi;
    if (hi <= tlo + P) return 1;
    out[1][0] = lo - P;
    out[1][1] = hi - P;
    return 2;
  };
  const int nx = wrap_range(q.lo.x, q.hi.x, tile_->lo_m.x, tile_->size_m.x, xs);
  const int ny = wrap_range(q.lo.y, q.hi.y, tile_->lo_m.y, tile_->size_m.y, ys);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (index_->any_overlaps(Aabb{{xs[i][0], ys[j][0], q.lo.z}, {xs[i][1], ys[j][1], q.hi.z}})) return true;
  return false;
}

std::vector<uint8_t>& CloudModel::far_points(const std::vector<std::array<double, 3>>& q) const {
  DensityScratch& t = density_scratch();
  const size_t n = q.size();
  std::vector<uint8_t>& far = t.far;
  far.assign(n, 0);
  if (!disp_[0] || n == 0) return far;
  // A point farther than `displacement` from every shape cannot be displaced into one: its
  // density is 0, so it needs no displacement noise (and no other noise). The shapes near the
  // whole batch are gathered once; each point then tests those its own box meets
  // (ShapeIndex::visits), the same shapes a search of the index would give it.
  std::vector<glm::dvec3>& m = t.m;
  m.resize(n);
  Aabb outer{glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
  for (size_t i = 0; i < n; ++i) {
    m[i] = wrapped(glm::dvec3(q[i][0], q[i][1], q[i][2]));
    outer.lo = glm::min(outer.lo, m[i]);
    outer.hi = glm::max(outer.hi, m[i]);
  }
  std::vector<uint32_t>& near_shapes = t.near_shapes;
  index_->candidates(outer.expanded(params_.displacement), near_shapes);
  // A point is near when any shape is; neighbours are mostly near the same one, so the shape
  // that made the last point near is tried first (the answer does not depend on the order).
  size_t last = 0;
  auto near_to = [&](size_t i, size_t j) {
    const uint32_t k = near_shapes[j];
    return index_->visits(Aabb{m[i], m[i]}.expanded(params_.displacement), k) &&
           !(grown_distance_bound(bound_shapes_[k], m[i]) > params_.displacement);
  };
  for (size_t i = 0; i < n; ++i) {
    bool is_far = true;
    if (!near_shapes.empty() && near_to(i, last)) {
      is_far = false;
    } else {
      for (size_t j = 0; j < near_shapes.size(); ++j)
        if (j != last && near_to(i, j)) {
          is_far = false;
          last = j;
          break;
        }
    }
    far[i] = is_far;
  }
  return far;
}

std::vector<double> CloudModel::far_test_key() const {
  const glm::dvec3 drift = params_.wind * time_;
  std::vector<double> key{drift.x, drift.y, drift.z, params_.shear.x, params_.shear.y, shear_base_, params_.displacement};
  key.push_back(tile_ ? 1.0 : 0.0);
  if (tile_) key.insert(key.end(), {tile_->lo_m.x, tile_->lo_m.y, tile_->size_m.x, tile_->size_m.y});
  key.push_back(double(shapes_.size()));
  for (const Shape& sh : shapes_)
    key.insert(key.end(), {double(sh.kind), sh.center.x, sh.center.y, sh.center.z, sh.size.x, sh.size.y, sh.size.z,
                           sh.end.x, sh.end.y, sh.end.z, sh.roughness, double(sh.rooted), sh.root_z, sh.root_taper});
  return key;
}

int64_t CloudModel::densities(const glm::dvec3* points, size_t n, float* out, uint8_t* far_io, bool far_known) const {
  const noise::BatchOptions serial{std::nullopt, false};  // callers parallelise over blocks
  DensityScratch& t = density_scratch();
  std::vector<std::array<double, 3>>& q = t.q;
  std::vector<double>& z0 = t.z0;  // the undisplaced altitude, where the base and the ceiling are level
  q.resize(n);
  z0.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 m = sheared(points[i]);
    q[i] = {m.x, m.y, m.z};
    z0[i] = m.z;
  }
  if (far_known) {
    t.far.assign(far_io, far_io + n);
  } else {
    far_points(q);
    if (far_io) std::copy(t.far.begin(), t.far.end(), far_io);
  }
  const std::vector<uint8_t>& far = t.far;
  if (disp_[0]) {
    std::vector<std::array<double, 3>>& near = t.near;
    near.clear();
    for (size_t i = 0; i < n; ++i)
      if (!far[i]) near.push_back(q[i]);
    // The three noises share a lattice: each point is split into cells once for all three.
    const std::array<const noise::NoiseField*, 3> fields{disp_[0].get(), disp_[1].get(), disp_[2].get()};
    for (int a = 0; a < 3; ++a) t.d[a].resize(near.size());
    const std::array<std::span<float>, 3> outs{std::span<float>(t.d[0]), std::span<float>(t.d[1]), std::span<float>(t.d[2])};
    noise::evaluate_points(fields, near, outs, serial);
    for (size_t i = 0, k = 0; i < n; ++i) {
      if (far[i]) continue;
      const glm::dvec3 d = displacement(t.d[0][k], t.d[1][k], t.d[2][k]);
      for (int a = 0; a < 3; ++a) q[i][a] += d[a];
      ++k;
    }
  }
  std::vector<double>& s = t.s;
  coverages(q, z0, far, s);
  std::vector<std::array<double, 3>>& busy = t.busy;
  std::vector<uint32_t>& where = t.where;
  busy.clear();
  where.clear();
  for (size_t i = 0; i < n; ++i) {
    out[i] = 0.0f;
    if (far[i]) continue;
    if (map_ && s[i] > 0.0) s[i] *= map_at(points[i]);  // the map: 0 leaves no cloud
    if (s[i] > min_useful_coverage_) {
      const glm::dvec3 m = noise_point({q[i][0], q[i][1], q[i][2]});
      busy.push_back({m.x, m.y, m.z});
      where.push_back(static_cast<uint32_t>(i));
    }
  }
  const int64_t evaluated = static_cast<int64_t>(busy.size());
  if (!busy.empty()) finish_busy(s, z0, out);
  if (n > kKeptPoints) t = DensityScratch{};  // a large batch gives its memory back
  return evaluated;
}

void CloudModel::finish_busy(const std::vector<double>& s, const std::vector<double>& z0, float* out) const {
  const noise::BatchOptions serial{std::nullopt, false};
  DensityScratch& t = density_scratch();
  const std::vector<std::array<double, 3>>& busy = t.busy;
  const std::vector<uint32_t>& where = t.where;
  std::vector<float>& nb = t.nb;
  nb.resize(busy.size());
  noise::evaluate_points(*billow_, busy, nb, serial);
  // Erosion, furrows and cauliflower only take density away: points whose billow already
  // leaves none (unbitten <= 0) stay 0 without them. The rest are evaluated in one batch.
  std::vector<std::array<double, 3>>& bitten = t.bitten;
  std::vector<uint32_t>& which = t.which;  // index into busy
  bitten.clear();
  which.clear();
  for (size_t k = 0; k < busy.size(); ++k) {
    if (unbitten(s[where[k]], calm(z0[where[k]]), nb[k]) > 0.0) {
      bitten.push_back(busy[k]);
      which.push_back(static_cast<uint32_t>(k));
    }
  }
  const size_t m = bitten.size();
  t.nd.assign(m, 0.0f);
  t.nr.assign(m, 0.0f);
  t.nc.assign(m, 1.0f);
  if (detail_) noise::evaluate_points(*detail_, bitten, t.nd, serial);
  if (furrow_) noise::evaluate_points(*furrow_, bitten, t.nr, serial);
  if (cauli_) cauli_->evaluate_points(bitten, t.nc, serial);
  for (size_t j = 0; j < m; ++j) {
    const uint32_t k = which[j], i = where[k];
    out[i] = finish(s[i], calm(z0[i]), nb[k], t.nd[j], t.nr[j], t.nc[j]);
  }
}

}  // namespace nimbus::volume

// The cloud density field (see cloud_model.hpp for the equations).
#include "nimbus/volume/cloud_model.hpp"

#include <algorithm>
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

std::unique_ptr<noise::NoiseField> make_field(noise::Kind kind, noise::Fractal fractal, int octaves,
                                              double frequency, double lacunarity, double gain,
                                              uint32_t seed, double evolution, double t,
                                              double voxel_size) {
  noise::NoiseParams n;
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
}

CloudModel::CloudModel(const CloudParams& params, double voxel_size, double time_seconds)
    : params_(params), time_(time_seconds) {
  validate(params_);
  need(std::isfinite(voxel_size) && voxel_size > 0, "voxel size must be finite and > 0 (metres)");
  need(std::isfinite(time_seconds), "time must be finite (seconds)");
  const CloudParams& p = params_;
  shapes_ = p.shapes;
  if (p.field) {
    const std::vector<Shape> f = field_shapes(*p.field, p.base_altitude > -1e29 ? p.base_altitude : 0.0);
    shapes_.insert(shapes_.end(), f.begin(), f.end());
  }
  shear_base_ = p.base_altitude > -1e29 ? p.base_altitude : 0.0;
  for (Shape& s : shapes_)
    if (s.rooted) s.root_z = shear_base_;  // turrets stand on the base
  index_ = std::make_unique<ShapeIndex>(shapes_);
  fibre_dir_ = p.stretch_direction / std::hypot(p.stretch_direction.x, p.stretch_direction.y);
  if (p.cauliflower > 0) {
    noise::PerlinWorleyParams pw;
    pw.frequency = p.cauliflower_frequency;
    pw.seed = p.seed + 7;
    if (p.evolution != 0.0) pw.time = p.evolution * time_;
    pw.perlin_octaves = noise::octaves_for_footprint(noise::perlin_part(pw), voxel_size).octaves;
    pw.worley_octaves = noise::octaves_for_footprint(noise::worley_part(pw), voxel_size).octaves;
    cauli_ = std::make_unique<noise::PerlinWorleyField>(pw);
  }
  billow_ = make_field(p.noise, noise::Fractal::Fbm, p.octaves, p.frequency, p.lacunarity, p.gain,
                       p.seed, p.evolution, time_, voxel_size);
  if (p.erosion > 0)
    detail_ = make_field(p.noise, noise::Fractal::Turbulence, 3, p.erosion_frequency, 2.0, 0.5,
                         p.seed + 1, p.evolution, time_, voxel_size);
  if (p.furrows > 0)
    furrow_ = make_field(p.noise, noise::Fractal::Ridged, 3, p.furrow_frequency, 2.0, 0.5, p.seed + 5,
                         p.evolution, time_, voxel_size);
  if (p.displacement > 0)
    for (int a = 0; a < 3; ++a)
      disp_[a] = make_field(noise::Kind::Gradient, noise::Fractal::Fbm, 3, p.displacement_frequency,
                            2.0, 0.5, p.seed + 2 + a, p.evolution, time_, voxel_size);
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

glm::dvec3 CloudModel::moved(const glm::dvec3& p) const {
  glm::dvec3 q = sheared(p);
  if (disp_[0])
    q += params_.displacement * glm::dvec3(disp_[0]->eval(q.x, q.y, q.z), disp_[1]->eval(q.x, q.y, q.z),
                                           disp_[2]->eval(q.x, q.y, q.z));
  return q;
}

namespace {

double smoothstep01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

}  // namespace

double CloudModel::coverage_at(const glm::dvec3& q, double z0) const {
  const CloudParams& p = params_;
  const bool under_ceiling = z0 > p.ceiling_altitude - p.ceiling_softness;
  const double ceiling = under_ceiling ? smoothstep01((p.ceiling_altitude - z0) / p.ceiling_softness) : 1.0;
  double s = 0.0;
  index_->visit(q, [&](uint32_t i) {
    const double c = shape_coverage(shapes_[i], q);
    s = std::max(s, shapes_[i].overshoot ? c : c * ceiling);
  });
  if (s > 0.0 && z0 < p.base_altitude + p.base_softness) s *= smoothstep01((z0 - p.base_altitude) / p.base_softness);
  return s;
}

double CloudModel::calm(double z0) const {
  const CloudParams& p = params_;
  if (!(p.flat_layer > 0.0)) return 1.0;
  const double above_base = p.base_altitude > -1e29 ? (z0 - p.base_altitude) / p.flat_layer : 1.0;
  const double below_ceiling = p.ceiling_altitude < 1e29 ? (p.ceiling_altitude - z0) / p.flat_layer : 1.0;
  return smoothstep01(std::min(above_base, below_ceiling));
}

float CloudModel::finish(double s, double w, float billow_noise, float detail, float furrow, float cauli) const {
  const double z = w * (double(billow_noise) - mean_) * inv_sd_ + (1.0 - w) * kBaseBillow;
  const double eaten = params_.erosion * double(detail) + params_.furrows * double(furrow) +
                       params_.cauliflower * (1.0 - double(cauli));
  const double f = s * (1.0 + params_.billow * z) - threshold_ - w * eaten;
  return gas_density(static_cast<float>(f), params_.gas);
}

float CloudModel::density(const glm::dvec3& p) const {
  const double z0 = sheared(p).z;
  const glm::dvec3 q = moved(p);
  const double s = coverage_at(q, z0);
  if (!(s > min_useful_coverage_)) return 0.0f;
  const glm::dvec3 m = noise_point(q);
  const float n = billow_->eval(m.x, m.y, m.z);
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
  return world_box(b);
}

bool CloudModel::may_touch(const Aabb& w) const {
  // The world box in q0 coordinates (the inverse of world_box), grown by the displacement.
  const glm::dvec3 shift = params_.wind * time_;
  const Aabb l = lean(w.lo.z - shift.z, w.hi.z - shift.z);
  const Aabb q{w.lo - shift - l.hi, w.hi - shift - l.lo};
  return index_->any_overlaps(q.expanded(params_.displacement));
}

int64_t CloudModel::densities(const glm::dvec3* points, size_t n, float* out) const {
  const noise::BatchOptions serial{std::nullopt, false};  // callers parallelise over blocks
  std::vector<std::array<double, 3>> q(n);
  std::vector<double> z0(n);  // the undisplaced altitude, where the base and the ceiling are level
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 m = sheared(points[i]);
    q[i] = {m.x, m.y, m.z};
    z0[i] = m.z;
  }
  // A point farther than `displacement` from every shape cannot be displaced into one: its
  // density is 0, so it needs no displacement noise (and no other noise).
  std::vector<uint8_t> far(n, 0);
  if (disp_[0]) {
    size_t kept = 0;
    for (size_t i = 0; i < n; ++i) {
      const glm::dvec3 m(q[i][0], q[i][1], q[i][2]);
      bool is_far = true;
      index_->visit(Aabb{m, m}.expanded(params_.displacement), [&](uint32_t k) {
        is_far = is_far && shape_distance_bound(shapes_[k], m) > params_.displacement;
      });
      far[i] = is_far;
      kept += !is_far;
    }
    std::vector<std::array<double, 3>> near;
    near.reserve(kept);
    for (size_t i = 0; i < n; ++i)
      if (!far[i]) near.push_back(q[i]);
    std::vector<float> d[3];
    for (int a = 0; a < 3; ++a) {
      d[a].resize(near.size());
      noise::evaluate_points(*disp_[a], near, d[a], serial);
    }
    for (size_t i = 0, k = 0; i < n; ++i) {
      if (far[i]) continue;
      for (int a = 0; a < 3; ++a) q[i][a] += params_.displacement * double(d[a][k]);
      ++k;
    }
  }
  std::vector<double> s(n);
  std::vector<std::array<double, 3>> busy;
  std::vector<uint32_t> where;
  for (size_t i = 0; i < n; ++i) {
    out[i] = 0.0f;
    if (far[i]) continue;
    s[i] = coverage_at({q[i][0], q[i][1], q[i][2]}, z0[i]);
    if (s[i] > min_useful_coverage_) {
      const glm::dvec3 m = noise_point({q[i][0], q[i][1], q[i][2]});
      busy.push_back({m.x, m.y, m.z});
      where.push_back(static_cast<uint32_t>(i));
    }
  }
  if (busy.empty()) return 0;
  std::vector<float> nb(busy.size()), nd(busy.size(), 0.0f), nr(busy.size(), 0.0f), nc(busy.size(), 1.0f);
  noise::evaluate_points(*billow_, busy, nb, serial);
  if (detail_) noise::evaluate_points(*detail_, busy, nd, serial);
  if (furrow_) noise::evaluate_points(*furrow_, busy, nr, serial);
  if (cauli_) cauli_->evaluate_points(busy, nc, serial);
  for (size_t k = 0; k < busy.size(); ++k) {
    const uint32_t i = where[k];
    out[i] = finish(s[i], calm(z0[i]), nb[k], nd[k], nr[k], nc[k]);
  }
  return static_cast<int64_t>(busy.size());
}

}  // namespace nimbus::volume

// Distances, coverage and bounds of the primitive shapes.
#include "nimbus/volume/shape.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "nimbus/noise/field.hpp"

namespace nimbus::volume {

Aabb Aabb::united(const Aabb& o) const {
  if (empty()) return o;
  if (o.empty()) return *this;
  return {glm::min(lo, o.lo), glm::max(hi, o.hi)};
}

bool Aabb::overlaps(const Aabb& o) const {
  return lo.x < o.hi.x && o.lo.x < hi.x && lo.y < o.hi.y && o.lo.y < hi.y && lo.z < o.hi.z &&
         o.lo.z < hi.z;
}

namespace {

// A rooted shape's lower pivot: where its column starts going down.
double pivot_z(const Shape& s) {
  return s.kind == ShapeKind::Capsule ? std::min(s.center.z, s.end.z) : s.center.z;
}

}  // namespace

double rooted_z(const Shape& s, double z) {
  if (!s.rooted) return z;
  const double pivot = pivot_z(s);
  if (z >= pivot || s.root_z >= pivot) return z;
  if (z >= s.root_z) return pivot;     // the column
  return z + (pivot - s.root_z);       // the underside, moved down to the root
}

double root_taper(const Shape& s, double z) {
  if (!s.rooted) return 1.0;
  const double pivot = pivot_z(s);
  if (z >= pivot || s.root_z >= pivot) return 1.0;
  return 1.0 - s.root_taper * std::min((pivot - z) / (pivot - s.root_z), 1.0);
}

double shape_distance(const Shape& s, const glm::dvec3& point) {
  // A rooted column narrows towards its root: the pivot's section, scaled about the axis.
  const double k = root_taper(s, point.z);
  const glm::dvec3 axis = s.kind == ShapeKind::Capsule && s.end.z < s.center.z ? s.end : s.center;
  const glm::dvec3 p(axis.x + (point.x - axis.x) / k, axis.y + (point.y - axis.y) / k, rooted_z(s, point.z));
  const glm::dvec3 d = p - s.center;
  switch (s.kind) {
    case ShapeKind::Ellipsoid: return glm::length(d / s.size);
    case ShapeKind::Capsule: {
      const glm::dvec3 ab = s.end - s.center;
      const double len2 = glm::dot(ab, ab);
      const double t = len2 > 0.0 ? std::clamp(glm::dot(d, ab) / len2, 0.0, 1.0) : 0.0;
      return glm::length(d - t * ab) / s.size.x;
    }
    case ShapeKind::Slab: {
      const glm::dvec3 q = glm::abs(d) / s.size;
      return std::max({q.x, q.y, q.z});
    }
    case ShapeKind::Lens: {
      // Thickness (1 - r^2) * size.z at radius r (in units of size.x): a lens with a sharp rim.
      const double r = std::sqrt(d.x * d.x + d.y * d.y) / s.size.x;
      const double h = std::max(1.0 - r * r, 1e-9) * s.size.z;
      return std::max(r, std::fabs(d.z) / h);
    }
  }
  return 2.0;
}

namespace {

const noise::NoiseField& roughness_noise_field() {
  static const noise::NoiseField field = [] {
    noise::NoiseParams n;
    n.kind = noise::Kind::Gradient;
    n.fractal = noise::Fractal::Fbm;
    n.octaves = 8;
    n.gain = kRoughnessGain;
    return noise::NoiseField(n);
  }();
  return field;
}

// Where the roughness noise of shape s is read for p: the shape's own units, offset per seed.
std::array<double, 3> roughness_point(const Shape& s, const glm::dvec3& p) {
  const double r = std::max(s.size.x, s.size.y);
  const glm::dvec3 l = (p - s.center) * (kRoughnessFrequency / r);
  const double o = double(s.roughness_seed % 4096u) * 37.0;  // lattice offset per seed
  return {l.x + o, l.y - o, l.z + 0.5 * o};
}

// The noise in [-1, 1]: fBm over two of its standard deviations, clamped.
double roughness_value(float n) {
  static const double inv = 0.5 / roughness_noise_field().expected_sd();
  return std::clamp(double(n) * inv, -1.0, 1.0);
}

}  // namespace

Shape bound_shape(const Shape& shape) {
  Shape s = shape;  // a rough outline reaches u = 1 + roughness: bound the shape grown by that factor
  s.size *= 1.0 + s.roughness;
  s.roughness = 0.0;
  return s;
}

double grown_distance_bound(const Shape& s, const glm::dvec3& p) {
  const double u = shape_distance(s, p);
  if (!(u > 1.0)) return 0.0;
  // A rooted column's taper divides horizontal offsets by up to 1 / (1 - root_taper): u changes
  // that much faster per metre, so the bound shrinks by that factor.
  const double taper = s.rooted ? 1.0 - s.root_taper : 1.0;
  switch (s.kind) {
    // u scales the offset by 1/size per axis, so a Euclidean step of length l changes u by at
    // most l / min(size): the boundary u = 1 is at least (u - 1) min(size) away.
    case ShapeKind::Ellipsoid:
    case ShapeKind::Slab: return taper * (u - 1.0) * std::min({s.size.x, s.size.y, s.size.z});
    case ShapeKind::Capsule: return taper * (u - 1.0) * s.size.x;  // u is distance / radius
    case ShapeKind::Lens: {
      // Outside the rim cylinder the horizontal distance bounds it; above or below the lens
      // no cheap bound is used.
      const double r = std::sqrt((p.x - s.center.x) * (p.x - s.center.x) + (p.y - s.center.y) * (p.y - s.center.y));
      return r > s.size.x ? r - s.size.x : 0.0;
    }
  }
  return 0.0;
}

double shape_distance_bound(const Shape& shape, const glm::dvec3& p) { return grown_distance_bound(bound_shape(shape), p); }

const noise::NoiseField& shape_roughness_noise() { return roughness_noise_field(); }

CoverageStart coverage_start(const Shape& s, const glm::dvec3& p) {
  CoverageStart c;
  c.u = shape_distance(s, p);
  if (s.roughness > 0.0) {
    if (!(c.u < 1.0 + s.roughness)) {
      c.zero = true;
      return c;
    }
    // Only near the outline; a rooted shape's column has the outline of its pivot's section.
    if (c.u > 1.0 - s.falloff - s.roughness) {
      c.needs_noise = true;
      c.noise_point = roughness_point(s, {p.x, p.y, rooted_z(s, p.z)});
    }
  }
  return c;
}

double coverage_finish(const Shape& s, const glm::dvec3& p, const CoverageStart& start, float noise) {
  if (start.zero) return 0.0;
  double u = start.u;
  if (start.needs_noise) u += s.roughness * roughness_value(noise);
  if (!(u < 1.0)) return 0.0;
  const double x = std::clamp((1.0 - u) / s.falloff, 0.0, 1.0);  // 0 at the boundary
  double c = s.weight * x * x * (3.0 - 2.0 * x);
  if (s.fade_up > 0.0) {
    const Aabb b = shape_bounds(s);
    const double h = std::clamp((b.hi.z - p.z) / (b.hi.z - b.lo.z), 0.0, 1.0);
    c *= std::pow(h, s.fade_up);
  }
  return c;
}

double shape_coverage(const Shape& s, const glm::dvec3& p) {
  const CoverageStart start = coverage_start(s, p);
  float n = 0.0f;
  if (!start.zero && start.needs_noise)
    n = roughness_noise_field().eval(start.noise_point[0], start.noise_point[1], start.noise_point[2]);
  return coverage_finish(s, p, start, n);
}

namespace {

// The bounds without the column of a rooted shape.
Aabb own_bounds(const Shape& shape) {
  Shape s = shape;  // a rough outline reaches u = 1 + roughness: the shape grown by that factor
  s.size *= 1.0 + s.roughness;
  switch (s.kind) {
    case ShapeKind::Ellipsoid:
    case ShapeKind::Slab: return {s.center - s.size, s.center + s.size};
    case ShapeKind::Capsule: {
      const glm::dvec3 r(s.size.x);
      return {glm::min(s.center, s.end) - r, glm::max(s.center, s.end) + r};
    }
    case ShapeKind::Lens: {
      const glm::dvec3 r(s.size.x, s.size.x, s.size.z);
      return {s.center - r, s.center + r};
    }
  }
  return {};
}

}  // namespace

Aabb shape_bounds(const Shape& shape) {
  Aabb b = own_bounds(shape);
  if (shape.rooted) b.lo.z -= std::max(0.0, pivot_z(shape) - shape.root_z);  // the column
  return b;
}

void validate(const Shape& s, const std::string& where) {
  auto finite = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(s.center)) throw std::invalid_argument(where + ".center must be finite");
  if (!finite(s.size) || !(s.size.x > 0 && s.size.y > 0 && s.size.z > 0))
    throw std::invalid_argument(where + ".size must be finite and > 0 on every axis");
  if (s.kind == ShapeKind::Capsule && !finite(s.end)) throw std::invalid_argument(where + ".end must be finite");
  if (!(s.falloff > 0.0 && s.falloff <= 1.0)) throw std::invalid_argument(where + ".falloff must be in (0, 1]");
  if (!(s.weight >= 0.0 && s.weight <= 1.0)) throw std::invalid_argument(where + ".weight must be in [0, 1]");
  if (!(s.fade_up >= 0.0 && s.fade_up <= 16.0)) throw std::invalid_argument(where + ".fade_up must be in [0, 16]");
  if (!(s.roughness >= 0.0 && s.roughness <= 1.0)) throw std::invalid_argument(where + ".roughness must be in [0, 1]");
  if (!std::isfinite(s.root_z)) throw std::invalid_argument(where + ".root_z must be finite (metres)");
  if (!(s.root_taper >= 0.0 && s.root_taper <= 0.5)) throw std::invalid_argument(where + ".root_taper must be in [0, 0.5]");
}

}  // namespace nimbus::volume

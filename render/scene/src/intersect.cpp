// Exact double-precision ray-scene intersection for the CPU reference: plane, box slab test,
// sphere (stable quadratic), heightfield triangles found by a 2D DDA over grid cells.
#include "nimbus/render/scene/intersect.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus::render {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Barycentric slack so a ray through the edge shared by two terrain triangles hits one of them
// (a leak there would let a shadow ray through the ground).
constexpr double kEdgeSlack = 1e-12;

glm::dvec3 hf_vertex(const Heightfield& h, int ix, int iz) {
  return {h.x0_m + ix * h.spacing_m, h.heights_m[static_cast<std::size_t>(iz) * h.nx + ix],
          h.z0_m + iz * h.spacing_m};
}

// Moller-Trumbore in double; t in units of d's length.
bool ray_triangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& v0, const glm::dvec3& v1,
                  const glm::dvec3& v2, double& t) {
  const glm::dvec3 e1 = v1 - v0, e2 = v2 - v0;
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0) return false;
  const double inv = 1.0 / det;
  const glm::dvec3 s = o - v0;
  const double u = glm::dot(s, p) * inv;
  if (u < -kEdgeSlack || u > 1.0 + kEdgeSlack) return false;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) * inv;
  if (v < -kEdgeSlack || u + v > 1.0 + kEdgeSlack) return false;
  t = glm::dot(e2, q) * inv;
  return true;
}

// Slab test against [lo, hi]: the parameter range inside, or false.
bool slab(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& o, const glm::dvec3& d,
          double& t0, double& t1) {
  t0 = -kInf;
  t1 = kInf;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (o[i] < lo[i] || o[i] > hi[i]) return false;
      continue;
    }
    const double inv = 1.0 / d[i];
    double ta = (lo[i] - o[i]) * inv, tb = (hi[i] - o[i]) * inv;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

// Heightfield traversal: cells visited in ray order (2D DDA in x, z); a cell's two triangles
// are tested only when the ray's height range over the cell overlaps the cell's heights.
// The first cell holding a hit holds the nearest one (its triangles lie in its column).
std::optional<Hit> traverse_heightfield(const Heightfield& h, const std::vector<double>& cmin,
                                        const std::vector<double>& cmax, double hmin, double hmax,
                                        const glm::dvec3& o, const glm::dvec3& d, double tmin,
                                        double tmax, bool any) {
  const double s = h.spacing_m;
  const glm::dvec3 lo{h.x0_m, hmin, h.z0_m};
  const glm::dvec3 hi{h.x0_m + (h.nx - 1) * s, hmax, h.z0_m + (h.nz - 1) * s};
  double ta, tb;
  if (!slab(lo, hi, o, d, ta, tb)) return std::nullopt;
  ta = std::max(ta, tmin);
  tb = std::min(tb, tmax);
  if (!(ta <= tb)) return std::nullopt;
  const glm::dvec3 p = o + ta * d;
  int ix = std::clamp(static_cast<int>(std::floor((p.x - h.x0_m) / s)), 0, h.nx - 2);
  int iz = std::clamp(static_cast<int>(std::floor((p.z - h.z0_m) / s)), 0, h.nz - 2);
  const int step_x = d.x > 0.0 ? 1 : -1, step_z = d.z > 0.0 ? 1 : -1;
  double next_x = kInf, next_z = kInf, delta_x = kInf, delta_z = kInf;
  if (d.x != 0.0) {
    next_x = (h.x0_m + (ix + (d.x > 0.0 ? 1 : 0)) * s - o.x) / d.x;
    delta_x = s / std::abs(d.x);
  }
  if (d.z != 0.0) {
    next_z = (h.z0_m + (iz + (d.z > 0.0 ? 1 : 0)) * s - o.z) / d.z;
    delta_z = s / std::abs(d.z);
  }
  double t_enter = ta;
  for (;;) {
    const double t_exit = std::min({next_x, next_z, tb});
    const std::size_t cell = static_cast<std::size_t>(iz) * (h.nx - 1) + ix;
    const double y0 = o.y + t_enter * d.y, y1 = o.y + t_exit * d.y;
    const double slack = 1e-9 * (1.0 + std::abs(y0) + std::abs(y1));
    if (std::max(y0, y1) >= cmin[cell] - slack && std::min(y0, y1) <= cmax[cell] + slack) {
      const glm::dvec3 p00 = hf_vertex(h, ix, iz), p10 = hf_vertex(h, ix + 1, iz);
      const glm::dvec3 p01 = hf_vertex(h, ix, iz + 1), p11 = hf_vertex(h, ix + 1, iz + 1);
      // Diagonal p00-p11; vertices counter-clockwise seen from above (normal = +y side).
      const glm::dvec3 tri[2][3] = {{p00, p11, p10}, {p00, p01, p11}};
      std::optional<Hit> best;
      for (const auto& v : tri) {
        double t;
        if (ray_triangle(o, d, v[0], v[1], v[2], t) && t > tmin && t < tmax &&
            (!best || t < best->t)) {
          best = Hit{t, glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0])), h.material.albedo};
          if (any) return best;
        }
      }
      if (best) return best;
    }
    if (t_exit >= tb) break;
    if (next_x < next_z) {
      ix += step_x;
      t_enter = next_x;
      next_x += delta_x;
    } else {
      iz += step_z;
      t_enter = next_z;
      next_z += delta_z;
    }
    if (ix < 0 || ix > h.nx - 2 || iz < 0 || iz > h.nz - 2) break;
  }
  return std::nullopt;
}

void cell_ranges(const Heightfield& h, std::vector<double>& cmin, std::vector<double>& cmax) {
  cmin.assign(static_cast<std::size_t>(h.nx - 1) * (h.nz - 1), 0.0);
  cmax.assign(cmin.size(), 0.0);
  for (int iz = 0; iz + 1 < h.nz; ++iz) {
    for (int ix = 0; ix + 1 < h.nx; ++ix) {
      const double a = hf_vertex(h, ix, iz).y, b = hf_vertex(h, ix + 1, iz).y;
      const double c = hf_vertex(h, ix, iz + 1).y, e = hf_vertex(h, ix + 1, iz + 1).y;
      const std::size_t k = static_cast<std::size_t>(iz) * (h.nx - 1) + ix;
      cmin[k] = std::min({a, b, c, e});
      cmax[k] = std::max({a, b, c, e});
    }
  }
}

}  // namespace

std::optional<Hit> intersect_plane(const GroundPlane& g, const glm::dvec3& o, const glm::dvec3& d,
                                   double tmin, double tmax) {
  if (d.y == 0.0) return std::nullopt;
  const double t = (g.height_m - o.y) / d.y;
  if (!(t > tmin && t < tmax)) return std::nullopt;
  return Hit{t, {0.0, 1.0, 0.0}, g.material.albedo, true};
}

std::optional<Hit> intersect_box(const Box& b, const glm::dvec3& o, const glm::dvec3& d, double tmin,
                                 double tmax) {
  double t0, t1;
  if (!slab(b.min_m, b.max_m, o, d, t0, t1)) return std::nullopt;
  double t;
  if (t0 > tmin && t0 < tmax) {
    t = t0;
  } else if (t1 > tmin && t1 < tmax) {
    t = t1;  // the ray starts inside the box
  } else {
    return std::nullopt;
  }
  // Outward normal of the face the hit point lies on (the one it is closest to, relative to
  // the box size, so edges and corners resolve deterministically).
  const glm::dvec3 p = o + t * d;
  const glm::dvec3 size = b.max_m - b.min_m;
  int axis = 0;
  double sign = 1.0, best = kInf;
  for (int i = 0; i < 3; ++i) {
    const double dl = std::abs(p[i] - b.min_m[i]) / size[i], dh = std::abs(p[i] - b.max_m[i]) / size[i];
    if (dl < best) best = dl, axis = i, sign = -1.0;
    if (dh < best) best = dh, axis = i, sign = 1.0;
  }
  glm::dvec3 n{0.0};
  n[axis] = sign;
  return Hit{t, n, b.material.albedo};
}

std::optional<Hit> intersect_sphere(const glm::dvec3& centre, double radius, const glm::dvec3& o,
                                    const glm::dvec3& d, double tmin, double tmax) {
  // t^2 a + 2 t B + C = 0 with the discriminant from the perpendicular distance (no
  // cancellation for far spheres) and the roots as q / a and C / q (no cancellation for the
  // near root).
  const glm::dvec3 oc = o - centre;
  const double a = glm::dot(d, d);
  const double B = glm::dot(oc, d);
  const double C = glm::dot(oc, oc) - radius * radius;
  const glm::dvec3 perp = oc - (B / a) * d;
  const double disc = a * (radius * radius - glm::dot(perp, perp));  // = B^2 - a C
  if (disc < 0.0) return std::nullopt;
  const double q = -(B + std::copysign(std::sqrt(disc), B));
  double r0, r1;
  if (q == 0.0) {
    r0 = r1 = 0.0;
  } else {
    r0 = q / a;
    r1 = C / q;
  }
  if (r0 > r1) std::swap(r0, r1);
  double t;
  if (r0 > tmin && r0 < tmax) {
    t = r0;
  } else if (r1 > tmin && r1 < tmax) {
    t = r1;
  } else {
    return std::nullopt;
  }
  return Hit{t, (o + t * d - centre) / radius, glm::dvec3{0.0}};
}

std::optional<Hit> intersect_heightfield(const Heightfield& h, const glm::dvec3& o, const glm::dvec3& d,
                                         double tmin, double tmax) {
  std::vector<double> cmin, cmax;
  cell_ranges(h, cmin, cmax);
  const auto [lo, hi] = std::minmax_element(h.heights_m.begin(), h.heights_m.end());
  return traverse_heightfield(h, cmin, cmax, *lo, *hi, o, d, tmin, tmax, false);
}

std::optional<double> heightfield_height(const Heightfield& h, double x, double z) {
  const double fx = (x - h.x0_m) / h.spacing_m, fz = (z - h.z0_m) / h.spacing_m;
  if (!(fx >= 0.0 && fz >= 0.0 && fx <= h.nx - 1 && fz <= h.nz - 1)) return std::nullopt;
  const int ix = std::min(static_cast<int>(fx), h.nx - 2), iz = std::min(static_cast<int>(fz), h.nz - 2);
  const double u = fx - ix, v = fz - iz;
  const double h00 = hf_vertex(h, ix, iz).y, h10 = hf_vertex(h, ix + 1, iz).y;
  const double h01 = hf_vertex(h, ix, iz + 1).y, h11 = hf_vertex(h, ix + 1, iz + 1).y;
  // Triangle (p00, p10, p11) where u >= v, else (p00, p01, p11): diagonal p00-p11.
  return u >= v ? h00 + u * (h10 - h00) + v * (h11 - h10) : h00 + v * (h01 - h00) + u * (h11 - h01);
}

SceneTracer::SceneTracer(const Scene& scene) : scene_(scene) {
  lo_ = glm::dvec3(kInf);
  hi_ = glm::dvec3(-kInf);
  for (const Box& b : scene.boxes) {
    lo_ = glm::min(lo_, b.min_m);
    hi_ = glm::max(hi_, b.max_m);
    has_bounds_ = true;
  }
  for (const Sphere& s : scene.spheres) {
    lo_ = glm::min(lo_, s.centre_m - s.radius_m);
    hi_ = glm::max(hi_, s.centre_m + s.radius_m);
    has_bounds_ = true;
  }
  if (scene.terrain) {
    const Heightfield& h = *scene.terrain;
    cell_ranges(h, cell_min_, cell_max_);
    const auto [mn, mx] = std::minmax_element(h.heights_m.begin(), h.heights_m.end());
    terrain_min_ = *mn;
    terrain_max_ = *mx;
    lo_ = glm::min(lo_, glm::dvec3{h.x0_m, terrain_min_, h.z0_m});
    hi_ = glm::max(hi_, glm::dvec3{h.x0_m + (h.nx - 1) * h.spacing_m, terrain_max_,
                                   h.z0_m + (h.nz - 1) * h.spacing_m});
    has_bounds_ = true;
  }
  if (has_bounds_) {
    // Outward by a relative margin so rounding in the slab test never culls a true hit.
    const glm::dvec3 pad = 1e-9 * (glm::abs(lo_) + glm::abs(hi_) + 1.0);
    lo_ -= pad;
    hi_ += pad;
  }
  auto add = [&](Occluder::Kind kind, std::size_t index, glm::dvec3 lo, glm::dvec3 hi) {
    const glm::dvec3 pad = 1e-6 + 1e-9 * (glm::abs(lo) + glm::abs(hi));
    occluders_.push_back({kind, index, lo - pad, hi + pad});
  };
  for (std::size_t i = 0; i < scene.boxes.size(); ++i) add(Occluder::BoxK, i, scene.boxes[i].min_m, scene.boxes[i].max_m);
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    add(Occluder::SphereK, i, s.centre_m - s.radius_m, s.centre_m + s.radius_m);
  }
  if (scene.terrain) {
    const Heightfield& h = *scene.terrain;
    add(Occluder::TerrainK, 0, {h.x0_m, terrain_min_, h.z0_m},
        {h.x0_m + (h.nx - 1) * h.spacing_m, terrain_max_, h.z0_m + (h.nz - 1) * h.spacing_m});
  }
}

void SceneTracer::occluder_bounds(std::size_t k, glm::dvec3& lo, glm::dvec3& hi) const {
  lo = occluders_[k].lo;
  hi = occluders_[k].hi;
}

bool SceneTracer::occluder_hit(std::size_t k, const glm::dvec3& o, const glm::dvec3& d, double tmax) const {
  const Occluder& oc = occluders_[k];
  switch (oc.kind) {
    case Occluder::BoxK:
      return intersect_box(scene_.boxes[oc.index], o, d, 0.0, tmax).has_value();
    case Occluder::SphereK: {
      const Sphere& s = scene_.spheres[oc.index];
      return intersect_sphere(s.centre_m, s.radius_m, o, d, 0.0, tmax).has_value();
    }
    case Occluder::TerrainK:
      return terrain_hit(o, d, 0.0, tmax, true).has_value();
  }
  return false;
}

bool SceneTracer::ground_hit(const glm::dvec3& o, const glm::dvec3& d, double tmax) const {
  return scene_.ground && intersect_plane(*scene_.ground, o, d, 0.0, tmax).has_value();
}

bool SceneTracer::finite_bounds(glm::dvec3& lo, glm::dvec3& hi) const {
  lo = lo_;
  hi = hi_;
  return has_bounds_;
}

std::optional<Hit> SceneTracer::terrain_hit(const glm::dvec3& o, const glm::dvec3& d, double tmin,
                                            double tmax, bool any) const {
  return traverse_heightfield(*scene_.terrain, cell_min_, cell_max_, terrain_min_, terrain_max_, o, d,
                              tmin, tmax, any);
}

std::optional<Hit> SceneTracer::intersect(const glm::dvec3& o, const glm::dvec3& d, double tmax,
                                          double tmin) const {
  std::optional<Hit> best;
  auto take = [&](const std::optional<Hit>& h) {
    if (h && h->t < tmax) {
      best = h;
      tmax = h->t;
    }
  };
  if (scene_.ground) take(intersect_plane(*scene_.ground, o, d, tmin, tmax));
  double b0, b1;
  if (!has_bounds_ || !slab(lo_, hi_, o, d, b0, b1) || b1 <= tmin || b0 >= tmax) return best;
  for (const Box& b : scene_.boxes) take(intersect_box(b, o, d, tmin, tmax));
  for (const Sphere& s : scene_.spheres) {
    auto h = intersect_sphere(s.centre_m, s.radius_m, o, d, tmin, tmax);
    if (h) h->albedo = s.material.albedo;
    take(h);
  }
  if (scene_.terrain) take(terrain_hit(o, d, tmin, tmax, false));
  return best;
}

bool SceneTracer::any_hit(const glm::dvec3& o, const glm::dvec3& d, double tmax) const {
  if (scene_.ground && intersect_plane(*scene_.ground, o, d, 0.0, tmax)) return true;
  double b0, b1;
  if (!has_bounds_ || !slab(lo_, hi_, o, d, b0, b1) || b1 <= 0.0 || b0 >= tmax) return false;
  for (const Box& b : scene_.boxes) {
    if (intersect_box(b, o, d, 0.0, tmax)) return true;
  }
  for (const Sphere& s : scene_.spheres) {
    if (intersect_sphere(s.centre_m, s.radius_m, o, d, 0.0, tmax)) return true;
  }
  return scene_.terrain && terrain_hit(o, d, 0.0, tmax, true).has_value();
}

bool SceneTracer::occluded(const glm::dvec3& from, const glm::dvec3& to) const {
  return any_hit(from, to - from, 1.0);
}

bool SceneTracer::occluded_toward(const glm::dvec3& from, const glm::dvec3& dir) const {
  return any_hit(from, dir, kInf);
}

std::optional<BulbHit> SceneTracer::intersect_bulbs(const glm::dvec3& o, const glm::dvec3& d,
                                                    double tmax) const {
  std::optional<BulbHit> best;
  for (std::size_t i = 0; i < scene_.lamps.size(); ++i) {
    const Light& l = scene_.lamps[i];
    if (!(l.bulb_radius_m > 0.0)) continue;  // no visible bulb
    if (auto h = intersect_sphere(l.position_m, l.bulb_radius_m, o, d, 0.0, tmax)) {
      best = BulbHit{h->t, i};
      tmax = h->t;
    }
  }
  return best;
}

std::optional<Hit> intersect(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& dir,
                             double tmax, double tmin) {
  return SceneTracer(scene).intersect(origin, dir, tmax, tmin);
}

bool occluded(const Scene& scene, const glm::dvec3& from, const glm::dvec3& to) {
  return SceneTracer(scene).occluded(from, to);
}

bool occluded_toward(const Scene& scene, const glm::dvec3& from, const glm::dvec3& dir) {
  return SceneTracer(scene).occluded_toward(from, dir);
}

std::optional<BulbHit> intersect_bulbs(const Scene& scene, const glm::dvec3& origin,
                                       const glm::dvec3& dir, double tmax) {
  return SceneTracer(scene).intersect_bulbs(origin, dir, tmax);
}

}  // namespace nimbus::render

// Exact double-precision ray-scene intersection for the CPU reference: ground plane, boxes
// (slab test), spheres (stable quadratic), heightfield triangles (2D grid DDA over cells), and
// shadow rays. Light bulbs are separate: they are seen but never occlude.
#pragma once
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {

// Nearest hit along origin + t * dir. normal is the unit geometric normal, outward for boxes
// and spheres and upward for the ground and terrain (not flipped toward the ray).
struct Hit {
  double t = 0.0;  // same unit as dir's length (metres for a unit dir)
  glm::dvec3 normal{0.0, 1.0, 0.0};
  glm::dvec3 albedo{0.0};
  bool ground = false;  // the ground plane (whose albedo may be a texture: ground_albedo.hpp)
};

// Nearest scene hit with tmin < t < tmax (tmax may be +inf). dir need not be unit; t is in
// units of dir's length. Bulbs are not part of the scene geometry.
std::optional<Hit> intersect(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& dir,
                             double tmax = std::numeric_limits<double>::infinity(),
                             double tmin = 0.0);

// True when the open segment from `from` to `to` meets scene geometry (bulbs never occlude).
bool occluded(const Scene& scene, const glm::dvec3& from, const glm::dvec3& to);
// True when the ray from `from` toward the direction `dir` (to infinity) meets geometry: the
// sun's shadow ray.
bool occluded_toward(const Scene& scene, const glm::dvec3& from, const glm::dvec3& dir);

// Nearest light bulb (Light::bulb_radius_m sphere) hit with 0 < t < tmax.
struct BulbHit {
  double t = 0.0;
  std::size_t light = 0;  // index into Scene::lamps
};
std::optional<BulbHit> intersect_bulbs(const Scene& scene, const glm::dvec3& origin,
                                       const glm::dvec3& dir,
                                       double tmax = std::numeric_limits<double>::infinity());

// The same queries on a scene prepared once (occluder bounds, per-cell terrain height ranges):
// what the reference renderer uses. Keeps a reference to the scene, which must outlive it.
class SceneTracer {
 public:
  explicit SceneTracer(const Scene& scene);
  const Scene& scene() const { return scene_; }
  std::optional<Hit> intersect(const glm::dvec3& origin, const glm::dvec3& dir,
                               double tmax = std::numeric_limits<double>::infinity(),
                               double tmin = 0.0) const;
  bool occluded(const glm::dvec3& from, const glm::dvec3& to) const;
  bool occluded_toward(const glm::dvec3& from, const glm::dvec3& dir) const;
  std::optional<BulbHit> intersect_bulbs(const glm::dvec3& origin, const glm::dvec3& dir,
                                         double tmax = std::numeric_limits<double>::infinity()) const;
  // Axis-aligned bounds of the finite occluders (boxes, spheres, terrain); false when there
  // are none (only the ground plane, or nothing).
  bool finite_bounds(glm::dvec3& lo, glm::dvec3& hi) const;

  // The finite occluders one by one (boxes, then spheres, then the terrain), for culling:
  // their bounds padded outward (1e-6 m + 1e-9 relative), and any hit with 0 < t < tmax.
  std::size_t occluder_count() const { return occluders_.size(); }
  void occluder_bounds(std::size_t k, glm::dvec3& lo, glm::dvec3& hi) const;
  bool occluder_hit(std::size_t k, const glm::dvec3& o, const glm::dvec3& d, double tmax) const;
  // Any hit of the ground plane with 0 < t < tmax.
  bool ground_hit(const glm::dvec3& o, const glm::dvec3& d, double tmax) const;

 private:
  struct Occluder {
    enum Kind { BoxK, SphereK, TerrainK } kind;
    std::size_t index;
    glm::dvec3 lo, hi;
  };
  std::vector<Occluder> occluders_;
  bool any_hit(const glm::dvec3& o, const glm::dvec3& d, double tmax) const;
  std::optional<Hit> terrain_hit(const glm::dvec3& o, const glm::dvec3& d, double tmin, double tmax,
                                 bool any) const;
  const Scene& scene_;
  bool has_bounds_ = false;
  glm::dvec3 lo_{0.0}, hi_{0.0};
  double terrain_min_ = 0.0, terrain_max_ = 0.0;
  std::vector<double> cell_min_, cell_max_;  // height range of each terrain cell (metres)
};

// The primitives, exposed for tests. Each returns the nearest t in (tmin, tmax) or nothing;
// dir need not be unit.
std::optional<Hit> intersect_plane(const GroundPlane& g, const glm::dvec3& o, const glm::dvec3& d,
                                   double tmin, double tmax);
std::optional<Hit> intersect_box(const Box& b, const glm::dvec3& o, const glm::dvec3& d, double tmin,
                                 double tmax);
std::optional<Hit> intersect_sphere(const glm::dvec3& centre, double radius, const glm::dvec3& o,
                                    const glm::dvec3& d, double tmin, double tmax);
std::optional<Hit> intersect_heightfield(const Heightfield& h, const glm::dvec3& o,
                                         const glm::dvec3& d, double tmin, double tmax);

// Height of the heightfield's triangle surface at (x, z) (same diagonal rule as the mesh), or
// nothing outside its rectangle.
std::optional<double> heightfield_height(const Heightfield& h, double x, double z);

}  // namespace nimbus::render

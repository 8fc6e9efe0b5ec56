// Primitive shapes that place gas in the world (Hoffmann 2007, slide "Plazierung"): each gives a
// coverage in [0, 1] that is 1 well inside, falls smoothly to 0 at its boundary ("fuzzy
// blobbies"), and is exactly 0 outside its bounding box. World units are metres, Z up.
#pragma once
#include <array>
#include <glm/vec3.hpp>
#include <string>

namespace nimbus::noise {
class NoiseField;
}

namespace nimbus::volume {

struct Aabb {
  glm::dvec3 lo{0.0}, hi{0.0};  // metres; empty when any lo >= hi
  bool empty() const { return !(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z); }
  Aabb expanded(double m) const { return {lo - glm::dvec3(m), hi + glm::dvec3(m)}; }
  Aabb united(const Aabb& o) const;
  bool overlaps(const Aabb& o) const;
};

enum class ShapeKind {
  Ellipsoid,  // centre, semi-axes `size`
  Capsule,    // segment centre..end, radius size.x
  Slab,       // box of half extents `size` around centre (a layer: large x, y)
  Lens,       // radius size.x (= y), half thickness size.z at the centre, thinning to the rim
};

struct Shape {
  ShapeKind kind = ShapeKind::Ellipsoid;
  glm::dvec3 center{0.0};  // metres
  glm::dvec3 size{1.0};    // metres (see ShapeKind)
  glm::dvec3 end{0.0};     // capsule: second end of the segment, metres
  double falloff = 0.3;    // share of the size over which coverage falls from 1 to 0, (0, 1]
  double weight = 1.0;     // peak coverage, [0, 1]
  // Altitude profile: coverage times ((top - z) / (top - bottom))^fade_up over the shape's
  // height (0: none). Steam and smoke thin out as they rise (Hoffmann 2007, the steaming teacup).
  double fade_up = 0.0;
  // Fractal outline: the normalised distance u is moved by up to +-roughness by gradient fBm
  // in the shape's own units (lattice cycles per horizontal semi-axis: kRoughnessFrequency,
  // gain kRoughnessGain, 8 octaves), so a small cloud is a scaled copy of a large one and every
  // outline is fractal from the cloud's size down (as real cloud outlines are: D about 1.35, Lovejoy 1982). [0, 1]; 0: smooth.
  double roughness = 0.0;
  uint32_t roughness_seed = 0;  // offsets the noise, so shapes differ
  // Convective: the shape rises from the cloud base. Below its lower pivot (an ellipsoid's or
  // lens's centre, a capsule's lower end) it continues straight down, at its widest section, to
  // root_z, and only below root_z does its own underside follow; so a turret is a column
  // standing on the base, and the model's cut at the condensation level (CloudModel) finds the
  // same full coverage in every column: the base is flat, as observed cumulus bases are
  // (Stull 2017, ch. 6: the base is the lifting condensation level).
  bool rooted = false;
  double root_z = 0.0;  // metres; the cloud model sets it to its base altitude
  // The column narrows towards the root, to (1 - root_taper) of the pivot's section at root_z:
  // cumulus are widest a little above their base, whose edge curves in. [0, 0.5]
  double root_taper = 0.0;
  // Pierces the model's ceiling (the tropopause): the overshooting dome of a cumulonimbus.
  bool overshoot = false;
};

// The altitude a rooted shape's distance is measured at (z itself for other shapes): a
// 1-Lipschitz map of z, so distance bounds hold.
double rooted_z(const Shape& s, double z);
// The horizontal scale of a rooted shape's section at altitude z (1 for other shapes).
double root_taper(const Shape& s, double z);

inline constexpr double kRoughnessFrequency = 1.5;
inline constexpr double kRoughnessGain = 0.7;

// A lower bound, in metres, of the distance from p to where the shape's coverage is non-zero
// (0 when p may be inside, or when no cheap bound is known).
double shape_distance_bound(const Shape& s, const glm::dvec3& p);
// The same bound in two halves, for many points against one shape: bound_shape(s) is the smooth
// shape that bounds s's rough outline (made once), and grown_distance_bound(bound_shape(s), p)
// equals shape_distance_bound(s, p).
Shape bound_shape(const Shape& s);
double grown_distance_bound(const Shape& grown, const glm::dvec3& p);

// Normalised distance u: < 1 inside, 1 on the boundary, > 1 outside.
double shape_distance(const Shape& s, const glm::dvec3& p);
// weight * smoothstep from 1 (at u = 1 - falloff) down to 0 (at u = 1).
double shape_coverage(const Shape& s, const glm::dvec3& p);

// shape_coverage in two halves around its roughness noise, so that a caller with many points
// can evaluate that noise in one batch (noise::evaluate_points on shape_roughness_noise(),
// which gives eval's bits): coverage_start says whether the coverage is 0 outright, gives u,
// and, where the outline is rough near p, the point at which the noise is needed;
// coverage_finish takes the noise's value there (ignored when none was needed).
struct CoverageStart {
  bool zero = false;          // the coverage is 0 whatever the noise
  double u = 0.0;             // shape_distance
  bool needs_noise = false;
  std::array<double, 3> noise_point{};  // where, in the roughness noise's lattice
};
CoverageStart coverage_start(const Shape& s, const glm::dvec3& p);
double coverage_finish(const Shape& s, const glm::dvec3& p, const CoverageStart& start, float noise);
const noise::NoiseField& shape_roughness_noise();
// The box outside which the coverage is exactly 0.
Aabb shape_bounds(const Shape& s);

// Throws std::invalid_argument naming the field for non-finite or non-positive sizes etc.
void validate(const Shape& s, const std::string& where);

}  // namespace nimbus::volume

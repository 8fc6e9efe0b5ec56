// The light-shaft scene: ground (plane or heightfield terrain), simple occluders (boxes,
// spheres) and its lights (light.hpp: the sun and lamps), inside a homogeneous medium. Units are
// metres, y up.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/media/atmosphere_tables.hpp"
#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/scene/ground_albedo.hpp"
#include "nimbus/render/core/light.hpp"
#include "nimbus/render/media/medium.hpp"

namespace nimbus::render {

// Lambertian surface colour (reflectance in [0, 1] per channel).
struct Material {
  glm::dvec3 albedo{0.6, 0.6, 0.6};
};

// Infinite horizontal plane y = height_m. With an albedo texture (ground_albedo.hpp) its albedo
// varies over the plane, filtered by each pixel's footprint, and `material` is unused; both
// renderers read the same texels.
struct GroundPlane {
  double height_m = 0.0;
  Material material;
  std::shared_ptr<const GroundAlbedoTexture> albedo_texture = nullptr;
};

// Heightfield terrain over [x0, x0 + (nx-1) dx] x [z0, z0 + (nz-1) dx], heights row-major
// (index = iz * nx + ix). Each cell is two triangles split along the diagonal from
// (ix, iz) to (ix+1, iz+1), so the GL mesh and the CPU reference see the same surface.
struct Heightfield {
  double x0_m = 0.0, z0_m = 0.0, spacing_m = 1.0;
  int nx = 0, nz = 0;
  std::vector<double> heights_m;
  Material material;
};

struct Box {  // axis-aligned
  glm::dvec3 min_m{0.0}, max_m{1.0};
  Material material;
};

struct Sphere {
  glm::dvec3 centre_m{0.0};
  double radius_m = 1.0;
  Material material;
};

// The sky behind everything: rays that meet no surface end at distance_m, where the sky's
// radiance shines through the fog. The fog ends there too: a surface beyond it (the ground
// toward the horizon) is seen through distance_m of fog, not hidden. Its radiance is a gradient from the horizon to the zenith,
// or, with an atmosphere, the physical sky's table (atmosphere_tables.hpp, Hillaire 2020).
struct Sky {
  glm::dvec3 zenith_radiance_w_sr_m2{0.04, 0.08, 0.2};
  glm::dvec3 horizon_radiance_w_sr_m2{0.22, 0.26, 0.32};
  double distance_m = 30000.0;  // where the fog ends, metres
  std::shared_ptr<const AtmosphereTables> atmosphere;  // set: the physical sky replaces the gradient
};

// Radiance of the sky in unit direction `dir` (y up): horizon + (zenith - horizon) sqrt(max(dir.y, 0)),
// or the sky-view table's. shaders/lib/sky.glsl computes the same.
glm::dvec3 sky_radiance(const Sky& sky, const glm::dvec3& dir);

// The sky's mean radiance over the upper hemisphere: (zenith + horizon) / 2 for the gradient,
// the table's integral for the physical sky. The ambient light on clouds.
glm::dvec3 sky_mean_radiance(const Sky& sky);

// The sky's light on a surface with unit normal n (y up), so that the ground in a cloud's shadow
// is lit by the sky, not black: the sky taken as uniform at a radiance Lm, and the surface
// seeing the share (1 + n.y) / 2 of it (a tilted plane's view of the upper hemisphere),
// unoccluded: E = pi Lm (1 + n.y) / 2, with Lm = (zenith + horizon) / 2 for the gradient and
// E_up / pi (the table's cosine-weighted integral) for the physical sky. Surfaces reflect
// albedo / pi E (surface.frag.glsl and the reference alike).
glm::dvec3 sky_irradiance(const Sky& sky, const glm::dvec3& n);

struct Scene {
  std::string name;
  Medium medium;
  std::optional<GroundPlane> ground;
  std::optional<Heightfield> terrain;
  std::vector<Box> boxes;
  std::vector<Sphere> spheres;
  // The scene's lights (light.hpp), the one set every renderer reads: lamps (LightKind::Point,
  // with their bulbs, spots among them) and at most one sun.
  std::vector<Light> lamps;
  std::optional<Light> sun;
  std::optional<Sky> sky;  // none: rays that meet nothing see black (through the fog's airlight)
  Camera camera;  // the scene's default view
  // The clouds' extinction per unit density the scene is made for (per metre; `nimbus render`'s
  // default for it): a hand-sized gas such as a cup's steam needs far more than a sky's clouds.
  // Such a scene's camera is aimed where its gas rises: `nimbus render` keeps it.
  std::optional<double> cloud_extinction_per_m;
};

// Throws std::invalid_argument naming the bad field (negative radius, inverted box, bad
// heightfield size, non-finite values, no light at all, a sun that is a lamp or a lamp that is a
// sun, a spot's cone outside 0 < inner <= outer <= pi, bad medium).
void validate(const Scene& scene);

// Named scenes for `nimbus render --scene NAME`.
std::vector<std::string> scene_names();
// Throws std::invalid_argument listing the known names when `name` is unknown.
Scene make_scene(const std::string& name);

}  // namespace nimbus::render

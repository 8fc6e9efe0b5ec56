// nimbus's one light model: the sun (parallel light of a given irradiance) or a lamp (a point
// light of radiant intensity I, falling off as I / r^2, optionally narrowed to a spot's cone).
// A scene owns its lights (scene.hpp: one sun at most, and lamps); the shafts, the surfaces, the
// clouds, the light volume and the path tracer all read them as this type. The clouds' renderers
// evaluate one through light_at() (shaders/lib/cloud_lamp.glsl is the same formulas in float).
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace nimbus::render {

enum class LightKind { Sun, Point };

// The shortest sun direction a Light takes (it is normalised on use, in floats on the GPU:
// shorter ones vanish there).
inline constexpr double kMinSunDirectionLength = 1e-12;

struct Light {
  // Sun: parallel light arriving from `direction_to_sun` (the one name and sign of the sun's
  // direction, from the sky file to the shaders), of irradiance `irradiance_w_m2` where it enters
  // the scene or the clouds. The medium attenuates view rays and scattered light, not the
  // sunlight itself (no finite fog top).
  glm::dvec3 direction_to_sun{0.3, 0.8, -0.5};  // normalised on use
  glm::dvec3 irradiance_w_m2{3.0};                 // per channel
  LightKind kind = LightKind::Sun;
  // Point: at `position_m`, radiant intensity `intensity_w_sr` per channel; the irradiance at
  // distance r is I / max(r, min_distance_m)^2 (the floor keeps a light inside a gas finite).
  glm::dvec3 position_m{0.0};
  glm::dvec3 intensity_w_sr{0.0};
  double min_distance_m = 1e-3;                    // > 0
  // Spot (a point light with a non-zero `spot_axis`): the light leaves along the unit axis
  // (propagation direction) at full intensity within `spot_inner_rad` of it, smoothstep to 0 at
  // `spot_outer_rad`: w = smoothstep(cos outer, cos inner, cos angle), 0 < inner <= outer <= pi.
  glm::dvec3 spot_axis{0.0};                       // zero: all directions (an isotropic lamp)
  double spot_inner_rad = 0.0, spot_outer_rad = 0.0;
  // A lamp seen directly is a small emissive sphere of this radius and radiance I / (pi r^2); the
  // bulb casts no shadow. 0 hides it (the benchmarks do, so that the error measures the shafts,
  // not the source). Clouds never see bulbs.
  double bulb_radius_m = 0.0;
};

// The sun, arriving from `direction_to_sun` with irradiance `irradiance_w_m2`.
Light sun_light(const glm::dvec3& direction_to_sun, const glm::dvec3& irradiance_w_m2);

// A lamp with a visible bulb of `bulb_radius_m` (a scene's street lamp).
Light bulb_light(const glm::dvec3& position_m, const glm::dvec3& intensity_w_sr, double bulb_radius_m);

// A lamp at `position_m` of intensity `intensity_w_sr`; a spot when `spot_axis` is non-zero.
Light point_light(const glm::dvec3& position_m, const glm::dvec3& intensity_w_sr,
                  const glm::dvec3& spot_axis = glm::dvec3(0.0), double spot_inner_rad = 0.0,
                  double spot_outer_rad = 0.0);

// Throws std::invalid_argument naming the field: non-finite values, a zero sun direction,
// negative irradiance or intensity, min_distance_m <= 0, a negative bulb radius, a spot's cones
// outside 0 < inner <= outer <= pi.
void validate(const Light& light);

// The light as it arrives, unshadowed, at world point x: the unit direction towards the light,
// the distance to it (infinite for the sun) and the irradiance on a plane facing it (W m^-2 per
// channel). The light's propagation direction at x is -to_light.
struct LightAtPoint {
  glm::dvec3 to_light{0.0, 1.0, 0.0};
  double distance_m = 0.0;
  glm::dvec3 irradiance_w_m2{0.0};
};
LightAtPoint light_at(const Light& light, const glm::dvec3& x);

// A lamp narrowed to a cone (a non-zero spot_axis); any among `lights`. The shaders compile a
// spot's cone and quadrature only for scenes that have one (SPOTS in lib/light_list.glsl).
bool is_spot(const Light& light);
bool any_spot(const std::vector<Light>& lights);

// A spot's cone is valid: 0 < spot_inner_rad <= spot_outer_rad <= pi, both finite (true for a
// lamp that is not a spot).
bool valid_spot_cone(const Light& light);

// A spot's weight for the unit propagation direction `dir` (1 for a lamp that is not a spot):
// smoothstep(cos outer, cos inner, dot(dir, axis)).
double spot_weight(const Light& light, const glm::dvec3& dir);

// The irradiance a light delivers at world point x, one number for ranking lights (the largest
// channel).
double light_strength_at(const Light& light, const glm::dvec3& x);

// Indices of at most `max_lights` lights, the strongest at `x` first (ties: in order).
std::vector<int> strongest_lights(const std::vector<Light>& lights, const glm::dvec3& x, int max_lights);

}  // namespace nimbus::render

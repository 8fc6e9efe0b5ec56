// The physical sky's tables (Hillaire 2020), built on the CPU in a few tens of milliseconds
// whenever the sun moves, and read the same way by the CPU renderers and the shaders
// (shaders/lib/atmosphere_map.glsl holds the maps):
//   transmittance 256 x 64       T to the top of the atmosphere over (altitude, view zenith);
//   multiple scattering 64 x 32  Psi_ms, the isotropic radiance of the light scattered twice or
//                                more, per unit solar irradiance, over (altitude, sun zenith);
//   sky view 192 x 108           the sky's radiance seen from the viewer's altitude over
//                                (azimuth from the sun, view zenith); below the horizon, the
//                                air in front of the distant ground and the sunlit ground;
//   aerial perspective 64x64x32  in-scattered radiance and transmittance from the viewer to a
//                                distance along each view direction (the haze in front of things).
// Every table is checked against render/reference/atmosphere_reference.hpp, the same model
// integrated by brute force in double precision (tests/cpu/test_atmosphere.cpp).
#pragma once
#include <glm/glm.hpp>

#include <memory>
#include <vector>

#include "nimbus/render/media/atmosphere.hpp"

namespace nimbus::render {

// A table of RGB values; coordinates in texels, 0 to size - 1 (atmosphere_map.glsl).
struct AtmosphereTable {
  int width = 0, height = 0, depth = 1;
  std::vector<glm::vec3> texels;  // x fastest, then y, then z
  const glm::vec3& at(int x, int y, int z = 0) const { return texels[(static_cast<size_t>(z) * height + y) * width + x]; }
  glm::vec3 bilinear(glm::vec2 coord, int z = 0) const;  // clamped to the edges
  glm::vec3 trilinear(glm::vec3 coord) const;
};

// The sky as seen from one viewer: its altitude and the sun.
struct AtmosphereView {
  double altitude_m = 2.0;
  glm::dvec3 direction_to_sun{0.0, 1.0, 0.0};  // y up, normalised on use
  double aerial_max_distance_m = 40000.0;      // the aerial-perspective table's reach
};

// Throws std::invalid_argument naming the field: altitude outside [0, thickness - 1 km],
// a zero or non-finite sun direction, a reach outside (0, 1e6] m.
void validate(const Atmosphere& a, const AtmosphereView& v);

struct AtmosphereTables {
  Atmosphere atmosphere;
  AtmosphereView view;
  AtmosphereTable transmittance, multiple_scattering, sky_view, aerial_scattering, aerial_transmittance;
  glm::dvec3 sky_irradiance_up_w_m2{0.0};     // the sky's light on an upward surface at the viewer
  glm::dvec3 sky_mean_radiance_w_sr_m2{0.0};  // the sky's mean radiance over the upper hemisphere
  struct Timing {  // wall time of each build, ms (reported, never asserted; 0 when reused)
    double transmittance_ms = 0.0, multiple_scattering_ms = 0.0, sky_view_ms = 0.0, aerial_perspective_ms = 0.0;
  } timing;
};

// Builds every table (TBB). The transmittance and multiple-scattering tables do not depend on
// the view: they are taken from `previous` when its atmosphere is the same. Throws
// std::invalid_argument on bad input.
std::shared_ptr<const AtmosphereTables> build_atmosphere_tables(const Atmosphere& a, const AtmosphereView& v,
                                                                const std::shared_ptr<const AtmosphereTables>& previous = nullptr);

// Lookups, as the shaders make them. Directions are y up; the sun's is the view's.
// Transmittance to the top of the atmosphere (rays below the horizon read the horizon's).
glm::dvec3 table_transmittance(const AtmosphereTables& t, double altitude_m, double mu);
// The sun's irradiance at an altitude, W m^-2: solar x transmittance x the visible share of its disc.
glm::dvec3 table_sun_irradiance(const AtmosphereTables& t, double altitude_m, double mu_s);
// Psi_ms per unit solar irradiance, sr^-1.
glm::dvec3 table_multiple_scattering(const AtmosphereTables& t, double altitude_m, double mu_s);
// The sky's radiance seen from the viewer toward unit direction dir, W sr^-1 m^-2 (no sun disc).
glm::dvec3 table_sky_radiance(const AtmosphereTables& t, const glm::dvec3& dir);
// From the viewer along unit dir to a distance: the air's in-scattered radiance and its transmittance.
struct AerialPerspective {
  glm::dvec3 inscattered_w_sr_m2{0.0};
  glm::dvec3 transmittance{1.0};
};
AerialPerspective table_aerial_perspective(const AtmosphereTables& t, const glm::dvec3& dir, double distance_m);

// The inverse maps of atmosphere_map.glsl, in double: the query at a texel.
struct TransmittanceTexel {
  double altitude_m, mu;
};
TransmittanceTexel transmittance_texel(const Atmosphere& a, int x, int y);
struct ViewTexel {
  double cos_phi, cos_theta;
};
ViewTexel view_texel(const Atmosphere& a, double viewer_altitude_m, double u, double v);

// The viewer-frame quantities of a direction: cosines of its azimuth from the sun and its zenith angle.
struct ViewAngles {
  double cos_phi, cos_theta, nu;  // nu = cos of the angle to the sun
};
ViewAngles view_angles(const glm::dvec3& direction_to_sun, const glm::dvec3& dir);

}  // namespace nimbus::render

// The sun and the sky for a sun position, so that the viewer's sun slider moves everything that
// depends on it: the sun's direction and colour on clouds and ground, the sky gradient behind
// them, and the ambient light on the clouds. A small clear-sky model, not a reference: the sun's
// irradiance is attenuated along Kasten & Young's relative air mass (1989) with RGB optical
// depths of Rayleigh scattering plus a little aerosol, and the sky's zenith and horizon radiance
// dim and redden as the sun sets. At 32 degrees elevation the sun is the sky scene's own
// (scene_presets.cpp) to within 2 %.
#pragma once
#include <glm/glm.hpp>

#include "nimbus/render/core/scene.hpp"

namespace nimbus::render {

// Unit direction towards the sun in nimbus's y-up world (x east, -z north): elevation above the
// horizon and azimuth clockwise from north, both in degrees.
glm::dvec3 sun_direction(double elevation_deg, double azimuth_deg);

// Kasten & Young (1989): air mass relative to the zenith, m = 1 / (sin h + 0.50572 (h + 6.07995)^-1.6364),
// h in degrees; finite down to h = -6 (where it is clamped).
double relative_air_mass(double elevation_deg);

struct Daylight {
  SunLight sun;                 // direction and irradiance (0 once the sun is 4 degrees below the horizon)
  Sky sky;                      // zenith and horizon radiance, distance 20 km
  glm::dvec3 ambient_w_sr_m2;   // the sky's mean radiance on a cloud: (zenith + horizon) / 2
};

// Throws std::invalid_argument for an elevation outside [-10, 90] or a non-finite azimuth.
Daylight daylight(double elevation_deg, double azimuth_deg);

}  // namespace nimbus::render

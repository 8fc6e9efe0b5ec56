// The sun and the sky for a sun position, so that the viewer's sun slider and the sky scene move
// everything that depends on it together: the sun's direction and colour on the ground and at
// the clouds, the sky behind them, and the ambient light on the clouds. All of it comes from the
// physical sky (atmosphere_tables.hpp, Hillaire 2020): the sun is the solar irradiance through
// the air's transmittance (reddened and dimmed as it sets, gone once its disc is below the
// horizon), the sky is the sky-view table, the ambient light is the sky's mean radiance.
#pragma once
#include <glm/glm.hpp>

#include <memory>

#include "nimbus/render/media/atmosphere_tables.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {

// Unit direction towards the sun in nimbus's y-up world (x east, -z north): elevation above the
// horizon and azimuth clockwise from north, both in degrees.
glm::dvec3 sun_direction(double elevation_deg, double azimuth_deg);

// Where the sky is seen from by default (the viewer's eye level, 2 m up) and where the clouds are
// lit (the presets' cumulus layer, 0.4-3 km up).
inline constexpr double kDaylightViewerAltitudeM = 2.0;
inline constexpr double kDaylightCloudAltitudeM = 1500.0;

struct Daylight {
  Light sun;                           // at the ground: direction and irradiance
  glm::dvec3 cloud_sun_irradiance_w_m2;   // the sun at the cloud layer (brighter and whiter near sunset);
                                          // the sky scene lights its ground with it too (a few % brighter)
  Sky sky;                                // the physical sky, ending 20 km away for the fog
  glm::dvec3 ambient_w_sr_m2;             // the sky's mean radiance over the upper hemisphere
  std::shared_ptr<const AtmosphereTables> tables;
};

// Throws std::invalid_argument for an elevation outside [-10, 90] or a non-finite azimuth.
// The tables of the last sun asked for are kept (one rebuild per new sun; the view-independent
// tables are built once).
// The sky is seen from viewer_altitude_m, in [0, 99 km].
Daylight daylight(double elevation_deg, double azimuth_deg, double viewer_altitude_m = kDaylightViewerAltitudeM);
Daylight daylight(const glm::dvec3& direction_to_sun,  // the elevation must be in [-10, 90] degrees
                  double viewer_altitude_m = kDaylightViewerAltitudeM);

}  // namespace nimbus::render

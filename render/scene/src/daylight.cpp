// The sun and sky for a sun position, from the physical sky (daylight.hpp).
#include "nimbus/render/scene/daylight.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

namespace nimbus::render {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// The tables of the last sun: the viewer asks every frame, the sun moves now and then.
std::shared_ptr<const AtmosphereTables> tables_for(const glm::dvec3& direction_to_sun, double viewer_altitude_m) {
  static std::mutex mutex;
  static std::shared_ptr<const AtmosphereTables> last;
  std::lock_guard<std::mutex> lock(mutex);
  // The tables keep the direction normalised again, which may move it by an ulp: compare with
  // that (an exact compare with the caller's missed every time, a rebuild per viewer frame).
  if (last && last->view.direction_to_sun == glm::normalize(direction_to_sun) && last->view.altitude_m == viewer_altitude_m)
    return last;
  AtmosphereView view;
  view.altitude_m = viewer_altitude_m;
  view.direction_to_sun = direction_to_sun;
  last = build_atmosphere_tables(Atmosphere{}, view, last);
  return last;
}

}  // namespace

glm::dvec3 sun_direction(double elevation_deg, double azimuth_deg) {
  const double h = elevation_deg * kDeg, a = azimuth_deg * kDeg;
  return {std::cos(h) * std::sin(a), std::sin(h), -std::cos(h) * std::cos(a)};
}

Daylight daylight(double elevation_deg, double azimuth_deg, double viewer_altitude_m) {
  if (!(elevation_deg >= -10.0 && elevation_deg <= 90.0))
    throw std::invalid_argument("sun elevation must be in [-10, 90] degrees, got " + std::to_string(elevation_deg));
  if (!std::isfinite(azimuth_deg)) throw std::invalid_argument("sun azimuth must be finite");
  return daylight(sun_direction(elevation_deg, azimuth_deg), viewer_altitude_m);
}

Daylight daylight(const glm::dvec3& direction_to_sun, double viewer_altitude_m) {
  const double len = glm::length(direction_to_sun);
  if (!(std::isfinite(len) && len > 1.0e-12)) throw std::invalid_argument("sun direction must be finite and non-zero");
  const glm::dvec3 s = direction_to_sun / len;
  if (s.y < std::sin(-10.0 * kDeg) - 1.0e-12)
    throw std::invalid_argument("sun elevation must be in [-10, 90] degrees, got " + std::to_string(std::asin(s.y) / kDeg));
  Daylight d;
  if (!(std::isfinite(viewer_altitude_m) && viewer_altitude_m >= 0.0 && viewer_altitude_m <= 99000.0))
    throw std::invalid_argument("sky viewer altitude must be in [0, 99000] m, got " + std::to_string(viewer_altitude_m));
  d.tables = tables_for(s, viewer_altitude_m);
  d.sun.direction_to_sun = s;
  d.sun.irradiance_w_m2 = table_sun_irradiance(*d.tables, 0.0, s.y);
  d.cloud_sun_irradiance_w_m2 = table_sun_irradiance(*d.tables, kDaylightCloudAltitudeM, s.y);
  d.sky.atmosphere = d.tables;
  d.sky.distance_m = 20000.0;
  // The gradient's two radiances, for code that reads them: the table at the zenith and 5 degrees up.
  d.sky.zenith_radiance_w_sr_m2 = table_sky_radiance(*d.tables, {0.0, 1.0, 0.0});
  const glm::dvec3 side = glm::length(glm::dvec2(s.x, s.z)) > 1e-9 ? glm::normalize(glm::dvec3(-s.z, 0.0, s.x)) : glm::dvec3(1, 0, 0);
  d.sky.horizon_radiance_w_sr_m2 = table_sky_radiance(*d.tables, glm::normalize(side + glm::dvec3(0.0, std::tan(5.0 * kDeg), 0.0)));
  d.ambient_w_sr_m2 = d.tables->sky_mean_radiance_w_sr_m2;
  return d;
}

}  // namespace nimbus::render

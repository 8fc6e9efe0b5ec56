// The sun and sky for a sun position (daylight.hpp).
#include "nimbus/render/core/daylight.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nimbus::render {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Optical depth of the atmosphere at the zenith per channel (R, G, B at about 650, 550, 450 nm):
// Rayleigh 0.05, 0.10, 0.22 (Bucholtz 1995) plus 0.1 of aerosol.
const glm::dvec3 kZenithDepth{0.15, 0.20, 0.32};
// Irradiance above the atmosphere, W m^-2 per channel, scaled so that the sun at 32 degrees
// matches the sky scene's 6 x (1, 0.95, 0.88).
const glm::dvec3 kTopIrradiance{7.9, 8.3, 9.5};
// A clear afternoon's gradient (a little bluer than the sky scene's hazy one), the reddened
// horizon of a low sun, and the night floor the sky dims to.
const glm::dvec3 kZenith{0.07, 0.15, 0.42}, kHorizon{0.40, 0.48, 0.62}, kHorizonLow{0.55, 0.38, 0.28};
const glm::dvec3 kNight{0.004, 0.006, 0.012};

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

glm::dvec3 sun_direction(double elevation_deg, double azimuth_deg) {
  const double h = elevation_deg * kDeg, a = azimuth_deg * kDeg;
  return {std::cos(h) * std::sin(a), std::sin(h), -std::cos(h) * std::cos(a)};
}

double relative_air_mass(double elevation_deg) {
  const double h = std::max(elevation_deg, -6.0);
  const double m = 1.0 / (std::sin(h * kDeg) + 0.50572 * std::pow(h + 6.07995, -1.6364));
  return std::max(m, 1.0);
}

Daylight daylight(double elevation_deg, double azimuth_deg) {
  if (!(elevation_deg >= -10.0 && elevation_deg <= 90.0))
    throw std::invalid_argument("sun elevation must be in [-10, 90] degrees, got " + std::to_string(elevation_deg));
  if (!std::isfinite(azimuth_deg)) throw std::invalid_argument("sun azimuth must be finite");
  Daylight d;
  d.sun.direction_to_sun = sun_direction(elevation_deg, azimuth_deg);
  const double m = relative_air_mass(elevation_deg);
  const double up = smoothstep(-4.0, 1.0, elevation_deg);  // the disc sinks below the horizon
  d.sun.irradiance_w_m2 = up * kTopIrradiance * glm::exp(-kZenithDepth * m);
  // The sky is lit by the sun through the same air: brightest with a high sun, reddest at the
  // horizon when the sun is low, dimming to the night floor through civil twilight.
  const double day = smoothstep(-8.0, 12.0, elevation_deg) * (0.55 + 0.45 * smoothstep(5.0, 32.0, elevation_deg)) /
                     (0.55 + 0.45 * smoothstep(5.0, 32.0, 32.0));
  const double low = 1.0 - smoothstep(2.0, 25.0, elevation_deg);
  d.sky.zenith_radiance_w_sr_m2 = kNight + day * kZenith * (1.0 - 0.35 * low);
  d.sky.horizon_radiance_w_sr_m2 = kNight + day * glm::mix(kHorizon, kHorizonLow, low);
  d.sky.distance_m = 20000.0;
  d.ambient_w_sr_m2 = 0.5 * (d.sky.zenith_radiance_w_sr_m2 + d.sky.horizon_radiance_w_sr_m2);
  return d;
}

}  // namespace nimbus::render

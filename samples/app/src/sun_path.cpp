// The sun's position for a time of day (sun_path.hpp).
#include "nimbus/app/sun_path.hpp"

#include <cmath>

#include <glm/glm.hpp>
#include <stdexcept>
#include <string>

namespace nimbus::app {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
}  // namespace

double solar_declination_deg(double day_of_year) {
  return 23.45 * std::sin(2.0 * kPi * (284.0 + day_of_year) / 365.0);
}

SunPosition sun_at(double hour, double latitude_deg, double day_of_year) {
  if (!std::isfinite(hour)) throw std::invalid_argument("time of day: must be a finite number of hours");
  if (!kLatitudeRangeDeg.holds(latitude_deg))
    throw std::invalid_argument("latitude: must be in " + volume::range_text(kLatitudeRangeDeg) + " degrees, got " +
                                number_text(latitude_deg));
  if (!std::isfinite(day_of_year)) throw std::invalid_argument("day of year: must be finite");
  const double lat = latitude_deg * kDeg, d = solar_declination_deg(day_of_year) * kDeg;
  const double h = 15.0 * kDeg * std::remainder(hour - 12.0, 24.0);  // hour angle, [-pi, pi]
  const double up = std::sin(lat) * std::sin(d) + std::cos(lat) * std::cos(d) * std::cos(h);
  const double east = -std::cos(d) * std::sin(h);
  const double north = std::cos(lat) * std::sin(d) - std::sin(lat) * std::cos(d) * std::cos(h);
  SunPosition s;
  // atan2 of the horizontal length keeps the elevation exact near the zenith, where asin(up) is not.
  s.elevation_deg = std::atan2(up, std::hypot(east, north)) / kDeg;
  const double az = std::atan2(east, north) / kDeg;  // (-180, 180]; 0 at the zenith, where it is undefined
  s.azimuth_deg = az < 0.0 ? az + 360.0 : az;
  if (s.azimuth_deg >= 360.0) s.azimuth_deg = 0.0;
  return s;
}

namespace {

// Unit vector (east, north, up) of a sun.
glm::dvec3 sun_vector(const SunPosition& p) {
  const double el = glm::radians(p.elevation_deg), az = glm::radians(p.azimuth_deg);
  return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
}

double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));  // stable near 0 and 180
}

}  // namespace

SunTime nearest_sun_time(const SunPosition& sun, double latitude_deg, double day_of_year) {
  const glm::dvec3 want = sun_vector(sun);
  const auto off = [&](double hour) { return angle_deg(want, sun_vector(sun_at(hour, latitude_deg, day_of_year))); };
  SunTime best{0.0, off(0.0)};
  for (int step = 1; step < 144; ++step) {  // every 10 minutes
    const double h = step / 6.0, d = off(h);
    if (d < best.off_path_deg) best = {h, d};
  }
  // Refine by golden-section search over the 20 minutes about it, to within a minute.
  double lo = best.hour - 1.0 / 6.0, hi = best.hour + 1.0 / 6.0;
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  while (hi - lo > 1.0 / 120.0) {
    const double a = hi - phi * (hi - lo), b = lo + phi * (hi - lo);
    if (off(a) < off(b)) hi = b;
    else lo = a;
  }
  const double h = 0.5 * (lo + hi), d = off(h);
  if (d < best.off_path_deg) best = {h, d};
  best.hour = std::fmod(best.hour + 24.0, 24.0);
  return best;
}

}  // namespace nimbus::app

// The time-of-day sun path (sun_path.hpp).
#include "nimbus/app/sun_path.hpp"

#include <algorithm>
#include <cmath>

namespace nimbus::app {

SunPosition sun_at_hour(double hour) {
  constexpr double kPi = 3.14159265358979323846;
  if (!std::isfinite(hour)) hour = 12.0;
  const double day = (hour - 6.0) / 12.0;  // 0 at sunrise, 1 at sunset
  SunPosition s;
  s.elevation_deg = std::clamp(60.0 * std::sin(kPi * day), -10.0, 60.0);
  s.azimuth_deg = std::fmod(std::fmod(90.0 + 180.0 * day, 360.0) + 360.0, 360.0);
  return s;
}

}  // namespace nimbus::app

// The sun's position for a time of day, a latitude and a day of the year: the textbook solar
// geometry (Cooper 1969's declination; Duffie & Beckman 2013, ch. 1.6), local solar time, no
// equation of time, no refraction. The viewer's time-of-day slider and `nimbus render
// --time-of-day` both use it. Azimuth is the compass bearing (0 north, 90 east), the convention of
// the sky file's sun azimuth; elevation is above the horizon.
#pragma once

#include "nimbus/volume/sky_ranges.hpp"

namespace nimbus::app {

// The ranges of the time-of-day controls (--time-of-day, --latitude, --day-of-year and the
// viewer's sliders), defined once; the sun itself keeps volume::kSunElevationRangeDeg.
inline constexpr volume::Range kHourRange{0.0, 24.0};          // local solar time, hours
inline constexpr volume::Range kLatitudeRangeDeg{-90.0, 90.0};  // north positive
inline constexpr volume::Range kDayOfYearRange{1.0, 366.0};     // 1 = 1 January

struct SunPosition {
  double elevation_deg = 0.0;  // [-90, 90]
  double azimuth_deg = 0.0;    // [0, 360)
};

// Defaults of the time-of-day control: 45 degrees north at the June solstice (day 172).
inline constexpr double kDefaultLatitudeDeg = 45.0;
inline constexpr double kDefaultDayOfYear = 172.0;

// The sun's declination on a day of the year (1 = 1 January; fractions allowed), degrees:
// 23.45 sin(360 (284 + n) / 365) (Cooper 1969).
double solar_declination_deg(double day_of_year);

// The sun at local solar time `hour` (any finite value; 12 is solar noon; it wraps every 24 h),
// at latitude_deg in [-90, 90] (north positive). With east, north, up the local axes, the
// hour angle H = 15 (hour - 12) degrees and the declination d:
//   up    = sin(lat) sin(d) + cos(lat) cos(d) cos(H)
//   east  = -cos(d) sin(H)
//   north = cos(lat) sin(d) - sin(lat) cos(d) cos(H)
// Throws std::invalid_argument naming the argument for a non-finite one or a latitude outside
// [-90, 90].
SunPosition sun_at(double hour, double latitude_deg = kDefaultLatitudeDeg, double day_of_year = kDefaultDayOfYear);

// The time of day whose sun (sun_at, at this latitude and day) is nearest a sun set by its
// elevation and azimuth, and how far that sun is from it, degrees: the viewer's time-of-day
// control follows the elevation and azimuth controls with it, and says when a sun they set is off
// the day's path. The nearest within a minute of time (a sweep of 10-minute steps, refined).
struct SunTime {
  double hour = 12.0;           // [0, 24)
  double off_path_deg = 0.0;    // angle between the given sun and that hour's
};
SunTime nearest_sun_time(const SunPosition& sun, double latitude_deg = kDefaultLatitudeDeg,
                         double day_of_year = kDefaultDayOfYear);

}  // namespace nimbus::app

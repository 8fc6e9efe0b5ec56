// app::nearest_sun_time (samples/app/sun_path.hpp), the inverse of sun_at that keeps the viewer's
// time-of-day control consistent with a sun set by elevation and azimuth: a sun on the day's path
// gives back its hour within a minute and lies on the path; one no hour of that day has is named
// off it, by how much, at the nearest hour.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "nimbus/app/sun_path.hpp"

namespace nimbus::app {
namespace {

TEST(SunTime, ASunOnTheDaysPathGivesBackItsHour) {
  for (double latitude : {45.0, -33.9, 0.0, 60.0})
    for (double day : {172.0, 355.0, 80.0})
      for (double hour : {6.75, 9.1, 12.0, 12.5, 16.8, 23.2}) {
        const SunTime t = nearest_sun_time(sun_at(hour, latitude, day), latitude, day);
        EXPECT_NEAR(t.hour, hour, 1.0 / 60.0) << "lat " << latitude << " day " << day;
        EXPECT_LT(t.off_path_deg, 0.05) << "lat " << latitude << " day " << day << " hour " << hour;
        EXPECT_GE(t.hour, 0.0);
        EXPECT_LT(t.hour, 24.0);
      }
}

double angle_between(const SunPosition& a, const SunPosition& b) {
  const double d = std::acos(0.0) / 90.0;
  const double ea = a.elevation_deg * d, eb = b.elevation_deg * d, da = (a.azimuth_deg - b.azimuth_deg) * d;
  return std::acos(std::clamp(std::sin(ea) * std::sin(eb) + std::cos(ea) * std::cos(eb) * std::cos(da), -1.0, 1.0)) / d;
}

// At 45 N on the June solstice the sun is never 5 degrees up in the north (it is under the
// horizon at midnight): the nearest hour's sun is far from it. Neither does it stand 35 degrees
// up in the south-east (it is 60 up by the time it is there): the viewer's default sun is 24
// degrees off the default day's path, which the control now says. In both the hour given is the
// nearest: its sun is no farther than those a quarter of an hour either side.
TEST(SunTime, ASunOffThePathIsNamedOffIt) {
  for (const SunPosition sun : {SunPosition{5.0, 0.0}, SunPosition{35.0, 135.0}}) {
    const SunTime t = nearest_sun_time(sun);
    EXPECT_GT(t.off_path_deg, 10.0);
    EXPECT_NEAR(t.off_path_deg, angle_between(sun, sun_at(t.hour)), 1e-6);
    EXPECT_LE(t.off_path_deg, angle_between(sun, sun_at(t.hour + 0.25)) + 1e-9);
    EXPECT_LE(t.off_path_deg, angle_between(sun, sun_at(t.hour - 0.25)) + 1e-9);
  }
  EXPECT_LT(nearest_sun_time({35.0, 135.0}).hour, 12.0);  // a morning sun
}

}  // namespace
}  // namespace nimbus::app

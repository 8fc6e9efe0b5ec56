// The sun over a day, for a time-of-day control: a simple path, not an ephemeris. It rises due
// east at 6 h, stands 60 degrees high in the south at noon and sets due west at 18 h; below the
// horizon (down to -10 degrees) before 6 h and after 18 h. Azimuth is the compass bearing
// (0 north, 90 east), the convention of the sky file's sun_azimuth_deg.
#pragma once

namespace nimbus::app {

struct SunPosition {
  double elevation_deg = 0.0;  // [-10, 60]
  double azimuth_deg = 0.0;    // [0, 360)
};

// The sun at `hour` (local solar time in hours; the same formula outside 6-18 h, so the sun goes
// on below the horizon; a non-finite hour gives the noon sun).
SunPosition sun_at_hour(double hour);

}  // namespace nimbus::app

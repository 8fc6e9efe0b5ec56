// The sun's three spellings on the command line (sun_flags.hpp).
#include "sun_flags.hpp"

#include <cmath>

#include <glm/geometric.hpp>

#include "nimbus/app/sun_path.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/core/light.hpp"
#include "nimbus/render/core/world_axes.hpp"
#include "render_args.hpp"

namespace nimbus::cli {
namespace {

using volume::kSunAzimuthRangeDeg;
using volume::kSunElevationRangeDeg;

// Each flag's range is the one sky files, view states and the viewer use (sky_ranges.hpp, sun_path.hpp).
void check_range(const char* flag, const std::optional<double>& v, const volume::Range& range, const char* unit) {
  if (v && !range.holds(*v))
    throw UsageError(std::string(flag) + ": must be in " + volume::range_text(range) + " " + unit + ", got " + number_text(*v));
}

}  // namespace

void add_sun_options(CLI::App* cmd, SunArgs& a) {
  cmd->add_option("--sun", a.vector,
                  "Direction towards the sun X,Y,Z (Z up: 0,0,1 is noon overhead; replaces the scene's sun, adds one if it has none)");
  cmd->add_option("--sun-elevation", a.elevation_deg, "The sun's elevation above the horizon, degrees [-10, 90]");
  cmd->add_option("--sun-azimuth", a.azimuth_deg, "The sun's compass bearing, degrees [0, 360]: 0 north, 90 east (default 180, south)");
  cmd->add_option("--time-of-day", a.hour, "The sun at this local solar time, hours [0, 24] (with --latitude, --day-of-year)");
  cmd->add_option("--latitude", a.latitude_deg, "Latitude for --time-of-day, degrees, north positive (default 45)");
  cmd->add_option("--day-of-year", a.day_of_year, "Day of the year for --time-of-day, 1-366 (default 172, the June solstice)");
}

std::optional<glm::dvec3> sun_direction_of(const SunArgs& a) {
  const int ways = int(!a.vector.empty()) + int(a.elevation_deg.has_value()) + int(a.hour.has_value());
  if (ways > 1) throw UsageError("--sun, --sun-elevation, --time-of-day: give the sun one way, not " + std::to_string(ways));
  if (a.azimuth_deg && !a.elevation_deg) throw UsageError("--sun-azimuth: it goes with --sun-elevation, which was not given");
  if ((a.latitude_deg || a.day_of_year) && !a.hour)
    throw UsageError(std::string(a.latitude_deg ? "--latitude" : "--day-of-year") + ": it goes with --time-of-day, which was not given");
  check_range("--sun-elevation", a.elevation_deg, kSunElevationRangeDeg, "degrees");
  check_range("--sun-azimuth", a.azimuth_deg, kSunAzimuthRangeDeg, "degrees");
  check_range("--time-of-day", a.hour, app::kHourRange, "hours");
  check_range("--latitude", a.latitude_deg, app::kLatitudeRangeDeg, "degrees");
  check_range("--day-of-year", a.day_of_year, app::kDayOfYearRange, "days");
  if (!a.vector.empty()) {
    const glm::dvec3 world = parse_vec3("--sun", a.vector);
    // The direction is normalised where it is used, in floats: a shorter one vanishes there.
    if (!(glm::length(world) >= render::kMinSunDirectionLength))
      throw UsageError("--sun: '" + echo(a.vector) + "' is too short a direction (length " + number_text(glm::length(world)) +
                       ", below " + number_text(render::kMinSunDirectionLength) + "); give it at a usual scale, e.g. 0,0,1 overhead");
    return render::world_to_render(world);
  }
  if (a.elevation_deg) return render::sun_direction(*a.elevation_deg, a.azimuth_deg.value_or(180.0));
  if (a.hour) {
    const app::SunPosition s = app::sun_at(*a.hour, a.latitude_deg.value_or(app::kDefaultLatitudeDeg),
                                           a.day_of_year.value_or(app::kDefaultDayOfYear));
    if (s.elevation_deg < kSunElevationRangeDeg.lo)
      throw UsageError("--time-of-day: the sun is " + number_text(-s.elevation_deg) +
                       " degrees below the horizon then (nimbus renders suns down to " + number_text(-kSunElevationRangeDeg.lo) +
                       " degrees below)");
    return render::sun_direction(s.elevation_deg, s.azimuth_deg);
  }
  return std::nullopt;
}

}  // namespace nimbus::cli

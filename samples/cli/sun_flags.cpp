// The sun's three spellings on the command line (sun_flags.hpp).
#include "sun_flags.hpp"

#include <cmath>

#include <glm/geometric.hpp>

#include "nimbus/app/sun_path.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/daylight.hpp"
#include "nimbus/render/core/world_axes.hpp"
#include "render_args.hpp"

namespace nimbus::cli {
namespace {

// The lowest sun nimbus renders: the physical sky's tables end 10 degrees below the horizon.
constexpr double kLowestSunDeg = -10.0;

void check_range(const char* flag, const std::optional<double>& v, double lo, double hi, const char* unit) {
  if (v && !(*v >= lo && *v <= hi))
    throw UsageError(std::string(flag) + ": must be in [" + number_text(lo) + ", " + number_text(hi) + "] " + unit +
                     ", got " + number_text(*v));
}

}  // namespace

void add_sun_options(CLI::App* cmd, SunArgs& a) {
  cmd->add_option("--sun", a.vector,
                  "Direction towards the sun X,Y,Z (Z up: 0,0,1 is noon overhead; replaces the scene's sun, adds one if it has none)");
  cmd->add_option("--sun-elevation", a.elevation_deg, "The sun's elevation above the horizon, degrees [-10, 90]");
  cmd->add_option("--sun-azimuth", a.azimuth_deg, "The sun's compass bearing, degrees: 0 north, 90 east (default 180, south)");
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
  check_range("--sun-elevation", a.elevation_deg, kLowestSunDeg, 90.0, "degrees");
  if (a.azimuth_deg && !std::isfinite(*a.azimuth_deg)) throw UsageError("--sun-azimuth: must be a finite number of degrees");
  check_range("--time-of-day", a.hour, 0.0, 24.0, "hours");
  check_range("--latitude", a.latitude_deg, -90.0, 90.0, "degrees");
  check_range("--day-of-year", a.day_of_year, 1.0, 366.0, "days");
  if (!a.vector.empty()) {
    const glm::dvec3 world = parse_vec3("--sun", a.vector);
    if (!(glm::length(world) > 0.0)) throw UsageError("--sun: the direction must not be zero");
    return render::world_to_render(world);
  }
  if (a.elevation_deg) return render::sun_direction(*a.elevation_deg, a.azimuth_deg.value_or(180.0));
  if (a.hour) {
    const app::SunPosition s = app::sun_at(*a.hour, a.latitude_deg.value_or(app::kDefaultLatitudeDeg),
                                           a.day_of_year.value_or(app::kDefaultDayOfYear));
    if (s.elevation_deg < kLowestSunDeg)
      throw UsageError("--time-of-day: the sun is " + number_text(-s.elevation_deg) +
                       " degrees below the horizon then (nimbus renders suns down to 10 degrees below)");
    return render::sun_direction(s.elevation_deg, s.azimuth_deg);
  }
  return std::nullopt;
}

}  // namespace nimbus::cli

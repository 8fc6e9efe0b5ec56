// The sun of `nimbus render`, given one of three ways, all in nimbus's Z-up world: a direction
// (--sun X,Y,Z), a position in the sky (--sun-elevation DEG [--sun-azimuth DEG]), or a time of
// day (--time-of-day H [--latitude DEG] [--day-of-year N], the viewer's solar geometry,
// app/sun_path.hpp). The three give the same sun for the same position (tests/cpu/test_sun_flags.cpp).
#pragma once
#include <optional>
#include <set>
#include <string>

#include <glm/vec3.hpp>

#include "cli.hpp"

namespace nimbus::cli {

struct SunArgs {
  std::string vector;                     // --sun X,Y,Z: towards the sun, Z up
  std::optional<double> elevation_deg;    // --sun-elevation: above the horizon, [-10, 90]
  std::optional<double> azimuth_deg;      // --sun-azimuth: compass bearing, 0 north, 90 east (default 180)
  std::optional<double> hour;             // --time-of-day: local solar time, [0, 24]
  std::optional<double> latitude_deg;     // --latitude: [-90, 90] (default 45 N)
  std::optional<double> day_of_year;      // --day-of-year: [1, 366] (default 172, the June solstice)
};

void add_sun_options(CLI::App* cmd, SunArgs& args);

// The unit direction towards the sun in the renderer's frame (world_axes.hpp), or nullopt when no
// flag gives one. UsageError naming the flag for a bad value, two ways at once, a qualifier
// without what it qualifies (--latitude without --time-of-day), or a sun more than 10 degrees
// below the horizon (the sky's tables end there).
std::optional<glm::dvec3> sun_direction_of(const SunArgs& args);

}  // namespace nimbus::cli

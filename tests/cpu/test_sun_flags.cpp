// The sun of `nimbus render` given three ways (sun_flags.hpp) is one sun in one Z-up world: a
// direction, an elevation and azimuth, and a time of day at a latitude and day of the year give
// the same image, to the bit, as the direction they stand for; and --sun 0,0,1 is the noon sun
// overhead (it used to be a sun on the horizon, in the renderer's Y-up frame).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "nimbus/app/sun_path.hpp"
#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/core/world_axes.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "support/run_nimbus.hpp"

namespace nimbus::test {
namespace {

namespace fs = std::filesystem;

std::string exact(const glm::dvec3& v) {  // round-trip text of each component
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", v.x, v.y, v.z);
  return buf;
}

// A small steam plume over the sky scene: the sun lights the steam, colours the sky and the
// ground, so a different sun changes most pixels.
class SunFlags : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("nimbus_sun_flags_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  render::Image render_with(const std::string& sun_flags, const std::string& name) {
    const fs::path out = dir_ / (name + ".exr");
    const auto r = run_nimbus("render --preset steam --voxel-size 0.012 --res 48x32 --slices 24 --light-res 64 --scene sky " +
                              sun_flags + " -o " + out.string());
    EXPECT_EQ(r.code, 0) << sun_flags << "\n" << r.output;
    return render::read_exr(out);
  }

  fs::path dir_;
};

std::size_t differing(const render::Image& a, const render::Image& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i) n += a.rgba[i] != b.rgba[i];
  return n;
}

TEST_F(SunFlags, ElevationAzimuthAndTimeOfDayAreTheDirectionTheyStandFor) {
  // Elevation and azimuth: the direction of render::sun_direction, turned into the Z-up world.
  const render::Image by_angles = render_with("--sun-elevation 30 --sun-azimuth 120", "angles");
  const render::Image by_vector =
      render_with("--sun=" + exact(render::render_to_world(render::sun_direction(30.0, 120.0))), "vector");
  EXPECT_EQ(differing(by_angles, by_vector), 0u);

  // 9:30 solar time at 52 N in early May: the almanac's sun, as a direction.
  const app::SunPosition s = app::sun_at(9.5, 52.0, 125.0);
  ASSERT_GT(s.elevation_deg, 20.0);
  ASSERT_LT(s.azimuth_deg, 180.0);  // a morning sun stands east of south
  const render::Image by_time = render_with("--time-of-day 9.5 --latitude 52 --day-of-year 125", "time");
  const render::Image by_its_vector =
      render_with("--sun=" + exact(render::render_to_world(render::sun_direction(s.elevation_deg, s.azimuth_deg))), "time-vector");
  EXPECT_EQ(differing(by_time, by_its_vector), 0u);

  // Different suns give different pictures: the comparisons above can fail.
  EXPECT_GT(differing(by_angles, by_time), by_angles.rgba.size() / 2);
}

TEST_F(SunFlags, ZIsUp) {
  // --sun 0,0,1 is the sun overhead: the same picture as elevation 90, up to the azimuth's rounding
  // (cos 90 degrees is 6e-17, not 0), and the metadata gives it back as it was given.
  const render::Image up = render_with("--sun 0,0,1", "up");
  const render::Image overhead = render_with("--sun-elevation 90", "overhead");
  ASSERT_EQ(up.rgba.size(), overhead.rgba.size());
  for (std::size_t i = 0; i < up.rgba.size(); ++i)
    ASSERT_NEAR(up.rgba[i], overhead.rgba[i], 1e-4f * std::max(1.0f, std::abs(overhead.rgba[i]))) << i;
  EXPECT_NE(up.metadata.at("lights").find("sun towards 0,0,1 (z up)"), std::string::npos) << up.metadata.at("lights");
  // And north is +y: a sun low in the north (--sun 0,1,0.1) is the one at azimuth 0.
  const render::Image north = render_with("--sun 0,1,0.1", "north");
  const double elevation = std::atan2(0.1, 1.0) * 180.0 / 3.14159265358979323846;
  const render::Image north_angles = render_with("--sun-elevation " + std::to_string(elevation) + " --sun-azimuth 0", "north-angles");
  const render::Image south_angles = render_with("--sun-elevation " + std::to_string(elevation) + " --sun-azimuth 180", "south-angles");
  double north_diff = 0.0, south_diff = 0.0;
  for (std::size_t i = 0; i < north.rgba.size(); ++i) {
    north_diff = std::max(north_diff, double(std::abs(north.rgba[i] - north_angles.rgba[i])));
    south_diff = std::max(south_diff, double(std::abs(north.rgba[i] - south_angles.rgba[i])));
  }
  EXPECT_LT(north_diff, 0.01 * south_diff);
}

TEST_F(SunFlags, BadOrConflictingSunsAreUsageErrors) {
  const std::string base = "render --preset steam --voxel-size 0.012 --res 8x8 --scene sky -o " + (dir_ / "x.exr").string() + " ";
  const struct {
    std::string flags, names;
  } cases[] = {
      {"--sun 0,0,1 --sun-elevation 30", "give the sun one way"},
      {"--sun-elevation 30 --time-of-day 12", "give the sun one way"},
      {"--sun-azimuth 90", "--sun-azimuth: it goes with --sun-elevation"},
      {"--latitude 40", "--latitude: it goes with --time-of-day"},
      {"--day-of-year 40", "--day-of-year: it goes with --time-of-day"},
      {"--sun-elevation 95", "--sun-elevation: must be in [-10, 90]"},
      {"--sun-elevation 30 --sun-azimuth nan", "--sun-azimuth"},
      // The bearing's range is the sky file's and the view state's (volume/sky_ranges.hpp).
      {"--sun-elevation 30 --sun-azimuth 1e300", "--sun-azimuth: must be in [0, 360] degrees"},
      {"--sun-elevation 30 --sun-azimuth 360.5", "--sun-azimuth: must be in [0, 360] degrees"},
      {"--sun 1e-30,0,1e-30", "--sun: '1e-30,0,1e-30' is too short a direction"},
      {"--time-of-day 25", "--time-of-day: must be in [0, 24]"},
      {"--time-of-day 12 --latitude 91", "--latitude: must be in [-90, 90]"},
      {"--time-of-day 12 --day-of-year 0", "--day-of-year: must be in [1, 366]"},
      {"--time-of-day 0 --latitude 45 --day-of-year 172", "below the horizon"},
  };
  for (const auto& c : cases) {
    const auto r = run_nimbus(base + c.flags);
    EXPECT_EQ(r.code, 2) << c.flags << "\n" << r.output;
    EXPECT_NE(r.output.find(c.names), std::string::npos) << c.flags << "\n" << r.output;
  }
}

}  // namespace
}  // namespace nimbus::test

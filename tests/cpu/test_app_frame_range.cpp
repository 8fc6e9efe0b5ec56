// Frame ranges, job-array tasks and sequence file names of the app library
// (nimbus/app/frame_range.hpp, sequence_path.hpp), and the bench's noisy sphere
// (bench_clouds_scene.hpp), called directly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "nimbus/app/bench_clouds_scene.hpp"
#include "nimbus/app/frame_range.hpp"
#include "nimbus/app/sequence_path.hpp"
#include "nimbus/app/sun_path.hpp"

namespace nimbus::test {
namespace {

using app::FrameArgs;
using app::FrameRange;
using app::UsageError;

// The UsageError's text, or "" when `f` throws nothing.
template <class F>
std::string refusal(F f) {
  try {
    f();
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(AppFrameRange, FrameTimesCountFromTheStartFrame) {
  FrameArgs a;
  a.frames = "1001-1048";
  a.start_frame = 1001;
  a.fps = 24.0;
  const FrameRange r = app::parse_frames(a);
  EXPECT_TRUE(r.sequence);
  EXPECT_EQ(r.first, 1001);
  EXPECT_EQ(r.last, 1048);
  EXPECT_DOUBLE_EQ(r.time(1001), 0.0);
  EXPECT_DOUBLE_EQ(r.time(1025), 1.0);
  FrameArgs single;
  single.time = 12.5;
  const FrameRange s = app::parse_frames(single);
  EXPECT_FALSE(s.sequence);
  EXPECT_DOUBLE_EQ(s.time(7), 12.5);
}

// --time-scale spaces the frames in sky time: real time is 1 / fps (the default, and the times it
// always gave), a time-lapse 10 s a frame, a number that many seconds; anything else is refused.
TEST(AppFrameRange, TimeScaleSpacesTheFramesInSkyTime) {
  FrameArgs a;
  a.frames = "1001-1072";
  a.start_frame = 1001;
  a.fps = 24.0;
  EXPECT_DOUBLE_EQ(app::parse_frames(a).time(1072), 71.0 / 24.0);  // 3 s of film, 3 s of sky
  a.time_scale = "realtime";
  EXPECT_EQ(app::parse_frames(a).time(1072), 71.0 / 24.0);
  a.time_scale = "timelapse";
  EXPECT_DOUBLE_EQ(app::parse_frames(a).time(1072), 710.0);  // 3 s of film, 12 minutes of sky
  a.time_scale = "2.5";
  EXPECT_DOUBLE_EQ(app::parse_frames(a).time(1003), 5.0);
  const auto named = [](FrameArgs b) {
    const std::string why = refusal([&] { app::parse_frames(b); });
    EXPECT_EQ(why.rfind("--time-scale", 0), 0u) << b.time_scale << ": '" << why << "'";
  };
  for (const char* bad : {"0", "-1", "nan", "inf", "1e9", "fast", "2s"}) {
    FrameArgs b = a;
    b.time_scale = bad;
    named(b);
  }
  FrameArgs late = a;
  late.frames = "1001-13000";
  late.many_frames = true;
  late.time_scale = "86400";  // 12000 days: past the 1e9 s of sky time a sequence may span
  named(late);
  FrameArgs single;
  single.time = 3.0;
  single.time_scale = "timelapse";  // one picture has no frames to space
  named(single);
}

TEST(AppFrameRange, TheTasksOfAnArrayPartitionTheRange) {
  for (const int chunk : {1, 3, 7, 50}) {
    FrameArgs a;
    a.frames = "-5-40";
    a.chunk = chunk;
    a.frame_from_env = "NIMBUS_TEST_TASK_ID";
    const long tasks = app::task_count(-5, 40, chunk);
    int next = -5;
    for (long t = 0; t < tasks; ++t) {
      ::setenv("NIMBUS_TEST_TASK_ID", std::to_string(t).c_str(), 1);
      const FrameRange r = app::parse_frames(a);
      EXPECT_EQ(r.first, next) << "chunk " << chunk << " task " << t;
      EXPECT_GE(r.last, r.first);
      EXPECT_LE(r.last - r.first + 1, chunk);
      EXPECT_EQ(r.whole_first, -5);
      EXPECT_EQ(r.whole_last, 40);
      next = r.last + 1;
    }
    EXPECT_EQ(next, 41) << "chunk " << chunk;
    ::setenv("NIMBUS_TEST_TASK_ID", std::to_string(tasks).c_str(), 1);
    EXPECT_NE(refusal([&] { app::parse_frames(a); }).find("beyond the " + std::to_string(tasks) + " tasks"),
              std::string::npos);
  }
  ::unsetenv("NIMBUS_TEST_TASK_ID");
}

TEST(AppFrameRange, BadFlagsAreRefusedNamingTheFlag) {
  const auto named = [](FrameArgs a, const std::string& flag) {
    const std::string why = refusal([&] { app::parse_frames(a); });
    EXPECT_EQ(why.rfind(flag, 0), 0u) << "expected a refusal naming " << flag << ", got '" << why << "'";
  };
  FrameArgs a;
  a.frames = "1-10";
  a.fps = 1e-300;  // frame 10 would be 1e301 s from time 0
  named(a, "--fps");
  a.fps = 0.0;
  named(a, "--fps");
  a.fps = 24.0;
  a.frames = "10-1";
  named(a, "--frames");
  a.frames = "1-20000";
  named(a, "--frames");
  a.many_frames = true;
  EXPECT_EQ(refusal([&] { app::parse_frames(a); }), "");
  FrameArgs t;
  t.time = 1.0;
  t.frames = "1-2";
  named(t, "--time");
  FrameArgs env;
  env.frame_from_env = "SLURM_ARRAY_TASK_ID";
  named(env, "--frame-from-env");
  FrameArgs chunk;
  chunk.frames = "1-10";
  chunk.chunk = 2;
  named(chunk, "--chunk");
}

TEST(AppSequencePath, TheFrameFillsTheFieldOrGoesBeforeTheExtension) {
  EXPECT_EQ(app::sequence_path("o.%04d.exr", 7), "o.0007.exr");
  EXPECT_EQ(app::sequence_path("o_%d.vdb", 1234567), "o_1234567.vdb");
  EXPECT_EQ(app::sequence_path("out/cloud.vdb", 12), "out/cloud.0012.vdb");
  EXPECT_EQ(app::sequence_path("dir.v2/cloud", 3), "dir.v2/cloud.0003");
  EXPECT_EQ(app::sequence_path(".hidden", 3), ".hidden.0003");
  // Distinct frames never share a file name.
  EXPECT_NE(app::sequence_path("a.vdb", 1), app::sequence_path("a.vdb", 10));
  EXPECT_NE(app::sequence_path("a.%02d.vdb", 100), app::sequence_path("a.%02d.vdb", 10));
  EXPECT_EQ(refusal([] { app::sequence_path("a%099d.vdb", 7, "--preview"); }).rfind("--preview", 0), 0u);
  EXPECT_EQ(refusal([] { app::sequence_path("a.%04d.%04d.vdb", 7); }).rfind("-o", 0), 0u);
  EXPECT_FALSE(app::has_frame_field("plain.vdb"));
  EXPECT_TRUE(app::has_frame_field("f.%03d.vdb"));
}

// The bench's noisy sphere: n^3 active voxels, density in [0, 1], full at the centre and zero
// outside radius 0.47.
TEST(AppBenchScene, TheNoisySphereIsABoundedBallFilledAtItsCentre) {
  const int n = 24;
  const auto grid = app::bench_noisy_sphere(n);
  EXPECT_EQ(grid->activeVoxelCount(), openvdb::Index64(n) * n * n);
  const double voxel = 1.0 / n;
  auto acc = grid->getConstAccessor();
  int outside = 0;
  for (int k = -n / 2; k < n - n / 2; ++k)
    for (int j = -n / 2; j < n - n / 2; ++j)
      for (int i = -n / 2; i < n - n / 2; ++i) {
        const float d = acc.getValue(openvdb::Coord(i, j, k));
        ASSERT_GE(d, 0.0f);
        ASSERT_LE(d, 1.0f);
        const double x = (i + 0.5) * voxel, y = (j + 0.5) * voxel, z = (k + 0.5) * voxel;
        if (x * x + y * y + z * z >= 0.47 * 0.47) {
          EXPECT_EQ(d, 0.0f);
          ++outside;
        }
      }
  EXPECT_GT(outside, 0);
  EXPECT_EQ(acc.getValue(openvdb::Coord(0, 0, 0)), 1.0f);
  // The world position of voxel (0, 0, 0) is its centre, half a voxel from the origin.
  const openvdb::Vec3d c = grid->indexToWorld(openvdb::Vec3d(0.0));
  EXPECT_NEAR(c.x(), 0.5 * voxel, 1e-12);
}

// The sun's geometry (sun_path.hpp) against what any almanac says: on an equinox (declination 0)
// the sun rises due east at 6 h and sets due west at 18 h at every latitude; at solar noon it
// stands 90 - |latitude - declination| high, due south north of the subsolar point; the path is
// symmetric about noon and continuous; there is polar night and midnight sun.
TEST(AppSunPath, AgreesWithTheAlmanac) {
  EXPECT_NEAR(app::solar_declination_deg(81.0), 0.0, 1e-9);  // the March equinox of Cooper's formula
  EXPECT_NEAR(app::solar_declination_deg(172.0), 23.45, 0.01);
  EXPECT_NEAR(app::solar_declination_deg(355.0), -23.45, 0.01);
  for (double lat : {-60.0, -10.0, 0.0, 30.0, 52.0, 70.0}) {
    const app::SunPosition rise = app::sun_at(6.0, lat, 81.0), set = app::sun_at(18.0, lat, 81.0);
    EXPECT_NEAR(rise.elevation_deg, 0.0, 1e-9) << lat;
    EXPECT_NEAR(rise.azimuth_deg, 90.0, 1e-9) << lat;
    EXPECT_NEAR(set.elevation_deg, 0.0, 1e-9) << lat;
    EXPECT_NEAR(set.azimuth_deg, 270.0, 1e-9) << lat;
    for (double day : {1.0, 81.0, 172.0, 266.0, 355.0}) {
      const double d = app::solar_declination_deg(day);
      const app::SunPosition noon = app::sun_at(12.0, lat, day);
      EXPECT_NEAR(noon.elevation_deg, 90.0 - std::abs(lat - d), 1e-9) << lat << " " << day;
      EXPECT_NEAR(noon.azimuth_deg, lat > d ? 180.0 : 0.0, 1e-9) << lat << " " << day;
    }
  }
  EXPECT_LT(app::sun_at(12.0, 80.0, 355.0).elevation_deg, -13.0);  // polar night
  EXPECT_GT(app::sun_at(0.0, 80.0, 172.0).elevation_deg, 3.0);     // midnight sun, due north
  EXPECT_NEAR(app::sun_at(0.0, 80.0, 172.0).azimuth_deg, 0.0, 1e-9);
  for (double h = -30.0; h <= 54.0; h += 0.25) {
    const app::SunPosition s = app::sun_at(h, 45.0, 172.0), next = app::sun_at(h + 1e-6, 45.0, 172.0);
    const app::SunPosition mirror = app::sun_at(24.0 - h, 45.0, 172.0);
    EXPECT_GE(s.azimuth_deg, 0.0);
    EXPECT_LT(s.azimuth_deg, 360.0);
    EXPECT_NEAR(next.elevation_deg, s.elevation_deg, 1e-3) << h;
    EXPECT_NEAR(mirror.elevation_deg, s.elevation_deg, 1e-9) << h;
    EXPECT_NEAR(std::remainder(mirror.azimuth_deg + s.azimuth_deg, 360.0), 0.0, 1e-9) << h;
  }
  // Straight overhead at the subsolar point: elevation 90 without rounding trouble.
  EXPECT_NEAR(app::sun_at(12.0, app::solar_declination_deg(172.0), 172.0).elevation_deg, 90.0, 1e-9);
  for (const double bad : {std::nan(""), HUGE_VAL}) {
    EXPECT_THROW(app::sun_at(bad), std::invalid_argument);
    EXPECT_THROW(app::sun_at(12.0, bad), std::invalid_argument);
    EXPECT_THROW(app::sun_at(12.0, 45.0, bad), std::invalid_argument);
  }
  EXPECT_THROW(app::sun_at(12.0, 91.0), std::invalid_argument);
}

}  // namespace
}  // namespace nimbus::test

// `nimbus bench clouds` at toy sizes: the reference, vdb_render anchor, slicer grid, switch rows
// and popping sweep all run and print their rows; the slicer's error is small and falls with the
// slice count; bad options are usage errors (exit 2) naming the flag.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "support/run_nimbus.hpp"
#include "support/vdb_fixtures.hpp"
#include "test_gl_support.hpp"

namespace {

// The relative RMSE column (`column`: 5 in the sun's rows, 6 in the lamps', which add d) of the
// first table row starting with `prefix`.
double rel_rmse_of(const std::string& output, const std::string& prefix, int column = 5) {
  const std::size_t at = output.find(prefix);
  if (at == std::string::npos) return -1.0;
  std::istringstream row(output.substr(at, output.find('\n', at) - at));
  std::string cell;
  for (int i = 0; i <= column; ++i) std::getline(row, cell, '|');
  return std::stod(cell);
}

TEST(BenchClouds, ToyRunPrintsEveryPart) {
  NIMBUS_REQUIRE_GL();
  ASSERT_TRUE(std::filesystem::exists("/usr/bin/vdb_render"))
      << "/usr/bin/vdb_render is missing: install the Debian package libopenvdb-tools";
  nimbus::test::TempDir dir;
  const std::string plot = (dir / "plot.svg").string();
  const auto r = nimbus::test::run_nimbus(
      "bench clouds --res 32x32 --volume-res 16 --slices 8,32 --light-res 32 --repeat 1 --lights front "
      "--switch-slices 16 --switch-light-res 32 --sweep-half-deg 2 --sweep-step-deg 1 --lamp-distances 2,0.8 "
      "--lamp-slices 16,32 --steam-voxel 0.008 --plot " + plot);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* row : {"| reference (CPU", "| reference, steps doubled", "| vdb_render", "| slices (GL) | 8 slices",
                          "| slices (GL) | 32 slices", "multiple scattering, 2 octaves", "ratio switch / median",
                          "| front-lit | 2.00 | 32 slices", "| front-lit | 0.80 | 16 slices", "## Steam under the lamp"})
    EXPECT_NE(r.output.find(row), std::string::npos) << row << "\n" << r.output;
  const double coarse = rel_rmse_of(r.output, "| slices (GL) | 8 slices");
  const double fine = rel_rmse_of(r.output, "| slices (GL) | 32 slices");
  EXPECT_GT(coarse, fine) << r.output;
  EXPECT_LT(fine, 0.1) << r.output;
  const double lamp = rel_rmse_of(r.output, "| front-lit | 2.00 | 32 slices", 6);  // a column more: d
  EXPECT_GE(lamp, 0.0) << r.output;
  EXPECT_LT(lamp, 0.1) << r.output;
  EXPECT_TRUE(std::filesystem::exists(plot));
}

TEST(BenchClouds, BadOptionsAreUsageErrors) {
  for (const auto& [args, flag] : std::initializer_list<std::pair<const char*, const char*>>{
           {"bench clouds --slices 1", "--slices"},
           {"bench clouds --light-res 8,x", "--light-res"},
           {"bench clouds --lights side", "--lights"},
           {"bench clouds --repeat 0", "--repeat"},
           {"bench clouds --ref-steps 0.25", "--ref-steps"},
           {"bench clouds --format r8", "--format"},
           {"bench clouds --volume-res 4", "--volume-res"},
           {"bench clouds --lamp-distances 0.3", "--lamp-distances"},
           {"bench clouds --lamp-slices 1", "--lamp-slices"},
           {"bench clouds --steam-voxel 1", "--steam-voxel"}}) {
    const auto r = nimbus::test::run_nimbus(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(flag), std::string::npos) << args << "\n" << r.output;
  }
}

}  // namespace

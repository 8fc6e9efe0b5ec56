// `nimbus info`: grids, class, voxel size, value range and metadata of a written file (exit 0);
// a missing or damaged file is exit 1 naming it, bad usage exit 2.
#include <gtest/gtest.h>

#include <algorithm>

#include "nimbus/volume/vdb_io.hpp"
#include "support/run_nimbus.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using namespace nimbus::volume;
using nimbus::test::run_nimbus;
using nimbus::test::TempDir;

std::filesystem::path write_sample(const TempDir& dir) {
  auto density = openvdb::FloatGrid::create(0.0f);
  density->tree().setValueOn(openvdb::Coord(0, 0, 0), 0.25f);
  density->tree().setValueOn(openvdb::Coord(3, 1, 2), 5.5f);
  density->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
  ExportInfo info;
  info.preset = "stratus";
  info.seed = 99;
  const auto path = dir / "stratus.vdb";
  write_volume_vdb(path, {density}, info);
  return path;
}

TEST(VolumeIoCli, InfoPrintsGridClassVoxelSizeRangeAndMetadata) {
  TempDir dir;
  const auto path = write_sample(dir);
  const auto r = run_nimbus("info " + path.string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* want :
       {"grid density", "value type:     float", "class:          fog volume", "active voxels:  2",
        "index bbox:     (0, 0, 0) to (3, 1, 2), 4 x 2 x 3 voxels", "world bbox:     (-0.25, -0.25, -0.25) to (1.75, 0.75, 1.25)",
        "voxel size:     0.5", "value range:    0.25 to 5.5", "background:     0", "half float:     yes",
        "preset: stratus", "seed: 99", "up_axis: z", "units: metres", "nimbus checksum verified"})
    EXPECT_NE(r.output.find(want), std::string::npos) << want << "\n" << r.output;
}

TEST(VolumeIoCli, InfoGridSelectsOneGridAndAnUnknownNameIsAUsageError) {
  TempDir dir;
  const auto path = write_sample(dir);
  const auto ok = run_nimbus("info " + path.string() + " --grid density");
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_NE(ok.output.find("1 grid,"), std::string::npos) << ok.output;
  const auto bad = run_nimbus("info " + path.string() + " --grid smoke");
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("smoke"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("density (float)"), std::string::npos) << bad.output;
}

TEST(VolumeIoCli, InfoOnAMissingOrDamagedFileExitsOneNamingIt) {
  TempDir dir;
  const auto missing = dir / "missing.vdb";
  const auto r = run_nimbus("info " + missing.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find(missing.string()), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;

  const auto path = write_sample(dir);
  const std::string bytes = nimbus::test::read_bytes(path);
  nimbus::test::write_bytes(path, bytes.substr(0, bytes.size() / 2));
  const auto cut = run_nimbus("info " + path.string());
  EXPECT_EQ(cut.code, 1) << cut.output;
  EXPECT_NE(cut.output.find("truncated"), std::string::npos) << cut.output;
}

TEST(VolumeIoCli, InfoWithoutAFileIsAUsageError) {
  const auto r = run_nimbus("info");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("file"), std::string::npos) << r.output;
  EXPECT_EQ(run_nimbus("info --help").code, 0);
}

}  // namespace

// Files as downstream tools see them (docs/volume.md, "Files, as downstream tools expect them"):
// OpenVDB's own reader, vdb_print (libopenvdb-tools) and pyopenvdb (python3-openvdb) find a
// "density" fog volume with background 0, saved as half float with Blosc, the voxel size in
// metres and nimbus's file metadata. The tool checks are skipped when the tool is not installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "nimbus/volume/vdb_io.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using namespace nimbus::volume;
using nimbus::test::make_ball;
using nimbus::test::TempDir;

std::filesystem::path write_sample(const TempDir& dir) {
  const auto density = make_ball(16, 0.5);
  const auto temperature = make_ball(16, 0.5, "temperature");
  ExportInfo info;
  info.preset = "smoke_plume";
  info.seed = 7;
  info.time = 2.5;
  info.frame = 60;
  info.fps = 24.0;
  const auto path = dir / "plume.vdb";
  write_volume_vdb(path, {density, temperature}, info);
  return path;
}

TEST(VolumeIoConventions, OpenVdbReaderSeesAHalfFloatFogVolumeNamedDensity) {
  TempDir dir;
  const auto path = write_sample(dir);
  openvdb::io::File file(path.string());
  file.open(false);
  const auto meta = file.getMetadata();
  auto base = file.readGrid("density");
  auto temp = file.readGrid("temperature");
  file.close();
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(temp->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(grid->background(), 0.0f);
  EXPECT_TRUE(grid->saveFloatAsHalf());
  EXPECT_TRUE(grid->metaValue<bool>("is_saved_as_half_float"));
  EXPECT_DOUBLE_EQ(grid->voxelSize()[0], 0.5);
  EXPECT_EQ(grid->transform(), temp->transform());
  // The library's default compression; ZIP would be dropped for a fog volume anyway.
  EXPECT_EQ(grid->metaValue<std::string>("file_compression"), "blosc + active values");
  EXPECT_EQ(grid->getCreator(), std::string("nimbus ") + library_version());
  EXPECT_EQ(meta->metaValue<std::string>("creator"), std::string("nimbus ") + library_version());
  EXPECT_EQ(meta->metaValue<std::string>("preset"), "smoke_plume");
  EXPECT_EQ(meta->metaValue<int64_t>("seed"), 7);
  EXPECT_EQ(meta->metaValue<double>("time"), 2.5);
  EXPECT_EQ(meta->metaValue<int64_t>("frame"), 60);
  EXPECT_EQ(meta->metaValue<double>("fps"), 24.0);
  EXPECT_EQ(meta->metaValue<std::string>("up_axis"), "z");
  EXPECT_EQ(meta->metaValue<std::string>("units"), "metres");
  EXPECT_EQ(meta->metaValue<std::string>("nimbus_version"), library_version());
}

TEST(VolumeIoConventions, VdbPrintListsTheGridAndTheMetadata) {
  if (!std::filesystem::exists("/usr/bin/vdb_print")) GTEST_SKIP() << "vdb_print (libopenvdb-tools) not installed";
  TempDir dir;
  const auto path = write_sample(dir);
  const auto r = nimbus::test::run_command("/usr/bin/vdb_print -l -m " + path.string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* want : {"Name: density", "Name: temperature", "class: fog volume", "is_saved_as_half_float: true",
                           "file_compression: blosc + active values", "Background value: 0", "voxel size: 0.5",
                           "preset: smoke_plume", "seed: 7", "up_axis: z", "units: metres", "frame: 60",
                           "nimbus_version: ", "nimbus_checksum: crc32="})
    EXPECT_NE(r.output.find(want), std::string::npos) << want << "\n" << r.output;
}

TEST(VolumeIoConventions, PyOpenVdbReadsTheGridAndItsRange) {
  if (!std::filesystem::exists("/usr/bin/python3") ||
      nimbus::test::run_command("/usr/bin/python3 -c 'import pyopenvdb'").code != 0)
    GTEST_SKIP() << "pyopenvdb (python3-openvdb) not installed";
  TempDir dir;
  const auto path = write_sample(dir);
  const auto r = nimbus::test::run_command(
      "/usr/bin/python3 -c \"import sys, pyopenvdb as vdb; g = vdb.read(sys.argv[1], 'density'); "
      "lo, hi = g.evalMinMax(); m = vdb.readMetadata(sys.argv[1]); "
      "print(g.name, g.gridClass, g.background, g.saveFloatAsHalf, g.activeVoxelCount(), "
      "g.transform.voxelSize()[0], '%.3f %.3f' % (lo, hi), m['preset'], m['up_axis'], m['seed'])\" " +
      path.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto ball = make_ball(16, 0.5);
  float hi = 0;
  for (auto it = ball->cbeginValueOn(); it; ++it) hi = std::max(hi, *it);
  char range[64];
  std::snprintf(range, sizeof range, "%.3f", double(openvdb::math::half(hi)));
  const std::string want = "density fog volume 0.0 True " + std::to_string(ball->activeVoxelCount()) + " 0.5 ";
  EXPECT_EQ(r.output.rfind(want, 0), 0u) << r.output;
  EXPECT_NE(r.output.find(std::string(" ") + range + " smoke_plume z 7"), std::string::npos) << r.output;
}

}  // namespace

// Export refusals and atomic writes: bad grids are refused before anything is written (no NaN
// or Inf reaches a file, extra grids share the density grid's transform), and a failed write
// leaves no temporary file and never replaces a good file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <limits>

#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using namespace nimbus::volume;
using nimbus::test::count_temp_files;
using nimbus::test::make_ball;
using nimbus::test::read_bytes;
using nimbus::test::TempDir;

// Runs `write`, expects exception E whose message contains `mentions`.
template <class E, class F>
void expect_refused(F&& write, const std::string& mentions) {
  try {
    write();
    ADD_FAILURE() << "no exception; expected one mentioning " << mentions;
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
  }
}

TEST(VolumeIoAtomic, ExtraGridWithAnotherTransformIsRefusedByName) {
  TempDir dir;
  const auto density = make_ball(6, 0.5);
  auto temperature = make_ball(6, 0.25, "temperature");
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(dir / "a.vdb", {density, temperature}, {}); },
                                        "temperature");
  auto shifted = make_ball(6, 0.5, "flame");
  shifted->transform().postTranslate(openvdb::Vec3d(0.25, 0, 0));
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(dir / "a.vdb", {density, shifted}, {}); }, "flame");
  EXPECT_FALSE(std::filesystem::exists(dir / "a.vdb"));
  EXPECT_EQ(count_temp_files(dir.path), 0);
}

TEST(VolumeIoAtomic, NonFiniteAndOutOfRangeValuesAreRefusedByGridName) {
  TempDir dir;
  const auto density = make_ball(6, 0.5);
  for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    auto temperature = make_ball(6, 0.5, "temperature");
    temperature->tree().setValueOn(openvdb::Coord(1, 2, 3), bad);
    expect_refused<std::invalid_argument>([&] { write_volume_vdb(dir / "a.vdb", {density, temperature}, {}); },
                                          "temperature");
    // Inactive values reach the file too.
    auto hidden = make_ball(6, 0.5, "flame");
    hidden->tree().setValueOff(openvdb::Coord(40, 0, 0), bad);
    expect_refused<std::invalid_argument>([&] { write_volume_vdb(dir / "a.vdb", {density, hidden}, {}); }, "flame");
  }
  // 1e5 would become Inf as half float; as full float it is fine.
  auto big = make_ball(6, 0.5);
  big->tree().setValueOn(openvdb::Coord(0, 0, 0), 1e5f);
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(dir / "a.vdb", {big}, {}); }, "half-float");
  write_volume_vdb(dir / "full.vdb", {big}, {}, ExportOptions{.half_float = false});
  EXPECT_EQ(read_volume_vdb(dir / "full.vdb").grid->tree().getValue(openvdb::Coord(0, 0, 0)), 1e5f);
  EXPECT_FALSE(std::filesystem::exists(dir / "a.vdb"));
}

TEST(VolumeIoAtomic, BadGridSetsAndMetadataAreRefused) {
  TempDir dir;
  const auto density = make_ball(4, 0.5);
  auto p = dir / "a.vdb";
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {}, {}); }, "no grids");
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {make_ball(4, 0.5, "smoke")}, {}); }, "smoke");
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {density, make_ball(4, 0.5, "")}, {}); }, "name");
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {density, make_ball(4, 0.5, "density")}, {}); },
                                        "density");
  auto bg = openvdb::FloatGrid::create(1.0f);
  bg->setName("temperature");
  bg->setTransform(density->transform().copy());
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {density, bg}, {}); }, "background");
  ExportInfo info;
  info.extra = {{"seed", int64_t(1)}};
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {density}, info); }, "seed");
  info.extra = {{"nimbus_checksum", std::string("x")}};
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {density}, info); }, "nimbus_checksum");
  info = {};
  info.fps = 0.0;
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {density}, info); }, "fps");
  info = {};
  info.time = std::nan("");
  expect_refused<std::invalid_argument>([&] { write_volume_vdb(p, {density}, info); }, "time");
  EXPECT_FALSE(std::filesystem::exists(p));
}

TEST(VolumeIoAtomic, TargetThatIsADirectoryFailsAndLeavesNoTempFile) {
  TempDir dir;
  std::filesystem::create_directories(dir / "out.vdb");
  expect_refused<std::runtime_error>([&] { write_volume_vdb(dir / "out.vdb", {make_ball(4, 0.5)}, {}); }, "out.vdb");
  EXPECT_TRUE(std::filesystem::is_directory(dir / "out.vdb"));
  EXPECT_EQ(count_temp_files(dir.path), 0);
}

TEST(VolumeIoAtomic, UnwritableDirectoryFailsNamingTheFile) {
  // /proc refuses new files even to root.
  expect_refused<std::runtime_error>([&] { write_volume_vdb("/proc/nimbus_io_test.vdb", {make_ball(4, 0.5)}, {}); },
                                     "/proc/nimbus_io_test.vdb");
  EXPECT_FALSE(std::filesystem::exists("/proc/nimbus_io_test.vdb"));
}

TEST(VolumeIoAtomic, ReadOnlyDirectoryFailsAndLeavesNoTempFile) {
  TempDir dir;
  const auto ro = dir / "ro";
  std::filesystem::create_directories(ro);
  std::filesystem::permissions(ro, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (::access(ro.c_str(), W_OK) == 0) GTEST_SKIP() << "running as root: directory permissions do not apply";
  expect_refused<std::runtime_error>([&] { write_volume_vdb(ro / "a.vdb", {make_ball(4, 0.5)}, {}); }, "a.vdb");
  EXPECT_EQ(count_temp_files(ro), 0);
  EXPECT_FALSE(std::filesystem::exists(ro / "a.vdb"));
}

TEST(VolumeIoAtomic, RefusedWriteLeavesTheOldFileByteIdentical) {
  TempDir dir;
  const auto path = dir / "cloud.vdb";
  write_volume_vdb(path, {make_ball(8, 0.5)}, {});
  const std::string good = read_bytes(path);
  auto bad = make_ball(8, 0.5);
  bad->tree().setValueOn(openvdb::Coord(0, 0, 0), std::numeric_limits<float>::quiet_NaN());
  EXPECT_THROW(write_volume_vdb(path, {bad}, {}), std::invalid_argument);
  EXPECT_EQ(read_bytes(path), good);
  EXPECT_EQ(count_temp_files(dir.path), 0);
  EXPECT_TRUE(read_volume_vdb(path).checksum_verified);
}

TEST(VolumeIoAtomic, OverwritingAGoodFileReplacesItWhole) {
  TempDir dir;
  const auto path = dir / "cloud.vdb";
  write_volume_vdb(path, {make_ball(8, 0.5)}, {});
  write_volume_vdb(path, {make_ball(3, 0.5)}, {});
  EXPECT_EQ(read_volume_vdb(path).grid->activeVoxelCount(), make_ball(3, 0.5)->activeVoxelCount());
  EXPECT_EQ(count_temp_files(dir.path), 0);
}

}  // namespace

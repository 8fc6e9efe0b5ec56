// VDB round trip: a sparse ball of densities up to 5.7 written and read back. Half float keeps
// values to half precision, full float bit for bit; the active voxels, the transform and the
// file metadata come back unchanged, and equal input gives byte-identical files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "nimbus/base/memory.hpp"
#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using namespace nimbus::volume;
using nimbus::test::make_ball;
using nimbus::test::TempDir;

ExportInfo sample_info() {
  ExportInfo info;
  info.preset = "cumulus_humilis";
  info.seed = 42;
  info.time = 12.5;
  info.frame = 1001;
  info.fps = 24.0;
  info.extra = {{"nimbus_coverage", 0.35}, {"nimbus_genus", std::string("cumulus")}, {"nimbus_octaves", int64_t(6)}};
  return info;
}

// Every key written comes back with the same type and value (the file adds only the seal).
void expect_metadata_equal(const Metadata& written, const Metadata& read) {
  for (const auto& [key, value] : written) {
    const auto it = std::find_if(read.begin(), read.end(), [&](const auto& kv) { return kv.first == key; });
    ASSERT_NE(it, read.end()) << key;
    EXPECT_EQ(it->second, value) << key;
  }
  EXPECT_EQ(read.size(), written.size() + 1);  // + nimbus_checksum
}

void expect_same_active_voxels(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
  EXPECT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
  auto acc = b.getConstAccessor();
  for (auto it = a.cbeginValueOn(); it; ++it) ASSERT_TRUE(acc.isValueOn(it.getCoord())) << it.getCoord();
}

TEST(VolumeIoRoundTrip, HalfFloatKeepsValuesToHalfPrecision) {
  TempDir dir;
  const auto ball = make_ball(20, 0.25);
  const auto path = dir / "ball.vdb";
  const ExportInfo info = sample_info();
  write_volume_vdb(path, {ball}, info);  // half float is the default
  const VolumeFile f = read_volume_vdb(path);
  ASSERT_TRUE(f.grid);
  EXPECT_TRUE(f.checksum_verified);
  EXPECT_EQ(f.grid->getName(), "density");
  expect_same_active_voxels(*ball, *f.grid);
  auto acc = f.grid->getConstAccessor();
  float max_read = 0;
  for (auto it = ball->cbeginValueOn(); it; ++it) {
    const float want = *it, got = acc.getValue(it.getCoord());
    // Half: 11 significant bits (relative 2^-11); below the normal range the spacing is 2^-24.
    const float tol = std::max(std::fabs(want) * std::ldexp(1.0f, -11), std::ldexp(1.0f, -25));
    ASSERT_NEAR(got, want, tol) << it.getCoord();
    max_read = std::max(max_read, got);
  }
  EXPECT_GT(max_read, 5.0f);  // densities above 1 survive
  EXPECT_EQ(f.grid->transform(), ball->transform());
  expect_metadata_equal(export_metadata(info), f.metadata);
}

TEST(VolumeIoRoundTrip, FullFloatIsBitExact) {
  TempDir dir;
  const auto ball = make_ball(20, 0.25);
  const auto path = dir / "ball.vdb";
  write_volume_vdb(path, {ball}, sample_info(), ExportOptions{.half_float = false});
  const VolumeFile f = read_volume_vdb(path);
  expect_same_active_voxels(*ball, *f.grid);
  auto acc = f.grid->getConstAccessor();
  for (auto it = ball->cbeginValueOn(); it; ++it) {
    const float got = acc.getValue(it.getCoord());
    ASSERT_EQ(std::memcmp(&got, &*it, sizeof(float)), 0) << it.getCoord();
  }
  EXPECT_FALSE(f.grid->saveFloatAsHalf());
  expect_metadata_equal(export_metadata(sample_info()), f.metadata);
}

TEST(VolumeIoRoundTrip, HalfFileIsSmallerThanFullFloat) {
  TempDir dir;
  const auto ball = make_ball(20, 0.25);
  write_volume_vdb(dir / "half.vdb", {ball}, sample_info());
  write_volume_vdb(dir / "float.vdb", {ball}, sample_info(), ExportOptions{.half_float = false});
  const auto half = std::filesystem::file_size(dir / "half.vdb");
  const auto full = std::filesystem::file_size(dir / "float.vdb");
  std::printf("ball r=20 (%llu active voxels): half %llu B, float %llu B (%.0f %%)\n",
              static_cast<unsigned long long>(ball->activeVoxelCount()), static_cast<unsigned long long>(half),
              static_cast<unsigned long long>(full), 100.0 * double(half) / double(full));
  EXPECT_LT(half, full);
}

TEST(VolumeIoRoundTrip, ExtraGridsComeBackByName) {
  TempDir dir;
  const auto density = make_ball(12, 0.5);
  auto temperature = make_ball(12, 0.5, "temperature");
  const auto path = dir / "smoke.vdb";
  write_volume_vdb(path, {density, temperature}, sample_info());
  const VolumeFile f = read_volume_vdb(path, std::string("temperature"));
  EXPECT_EQ(f.grid->getName(), "temperature");
  EXPECT_EQ(f.grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  ASSERT_EQ(f.grids.size(), 2u);
  EXPECT_EQ(f.grids[0].name, "density");
  EXPECT_EQ(f.grids[1].name, "temperature");
  EXPECT_EQ(read_volume_vdb(path).grid->getName(), "density");  // the default
}

TEST(VolumeIoRoundTrip, SameInputGivesByteIdenticalFiles) {
  TempDir dir;
  const auto ball = make_ball(10, 0.5);
  write_volume_vdb(dir / "a.vdb", {ball}, sample_info());
  write_volume_vdb(dir / "b.vdb", {ball}, sample_info());
  EXPECT_EQ(nimbus::test::read_bytes(dir / "a.vdb"), nimbus::test::read_bytes(dir / "b.vdb"));
  ExportInfo other = sample_info();
  other.seed = 43;
  write_volume_vdb(dir / "c.vdb", {ball}, other);
  EXPECT_NE(nimbus::test::read_bytes(dir / "a.vdb"), nimbus::test::read_bytes(dir / "c.vdb"));
}

TEST(VolumeIoRoundTrip, CallerGridIsNotModified) {
  TempDir dir;
  auto ball = make_ball(6, 0.5);
  ball->setName("");
  write_volume_vdb(dir / "a.vdb", {ball}, sample_info());
  EXPECT_EQ(ball->getName(), "");
  EXPECT_EQ(ball->getGridClass(), openvdb::GRID_UNKNOWN);
  EXPECT_FALSE(ball->saveFloatAsHalf());
}

TEST(VolumeIoRoundTrip, DenseActiveBoxIsXFastest) {
  auto grid = openvdb::FloatGrid::create(0.0f);
  auto acc = grid->getAccessor();
  acc.setValue(openvdb::Coord(-2, 5, 10), 1.0f);
  acc.setValue(openvdb::Coord(1, 5, 10), 2.0f);  // +3 in x
  acc.setValue(openvdb::Coord(-2, 6, 10), 3.0f);  // +1 in y
  acc.setValue(openvdb::Coord(-2, 5, 12), 4.0f);  // +2 in z
  const DenseBox box = dense_active_box(*grid);
  EXPECT_EQ(box.origin, (std::array<int32_t, 3>{-2, 5, 10}));
  EXPECT_EQ(box.size, (std::array<int64_t, 3>{4, 2, 3}));
  ASSERT_EQ(box.values.size(), 24u);
  const auto at = [&](int x, int y, int z) { return box.values[size_t(x + 4 * (y + 2 * z))]; };
  EXPECT_EQ(at(0, 0, 0), 1.0f);
  EXPECT_EQ(at(3, 0, 0), 2.0f);
  EXPECT_EQ(at(0, 1, 0), 3.0f);
  EXPECT_EQ(at(0, 0, 2), 4.0f);
  EXPECT_EQ(at(1, 1, 1), 0.0f);
  double sum = 0;
  for (float v : box.values) sum += v;
  EXPECT_EQ(sum, 10.0);
  EXPECT_TRUE(dense_active_box(*openvdb::FloatGrid::create(0.0f)).values.empty());
}

TEST(VolumeIoRoundTrip, DenseBoxBeyondMemoryIsRefusedBeforeAllocating) {
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->tree().setValueOn(openvdb::Coord(0, 0, 0), 1.0f);
  grid->tree().setValueOn(openvdb::Coord(1 << 20, 1 << 20, 1 << 20), 1.0f);  // 2^60 voxels apart
  try {
    dense_active_box(*grid);
    FAIL() << "expected OutOfMemoryRequest";
  } catch (const nimbus::OutOfMemoryRequest& e) {
    EXPECT_NE(std::string(e.what()).find("dense copy"), std::string::npos) << e.what();
  }
}

}  // namespace

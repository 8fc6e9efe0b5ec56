// Up axis on export: nimbus is Z-up; up = 'y' turns world +Z into +Y by the proper rotation
// (x, y, z) -> (x, z, -y), moving voxels exactly and keeping the voxel size, and records
// up_axis in the file metadata (VDB files have no up-axis field: Houdini is Y-up, Blender Z-up).
#include <gtest/gtest.h>

#include "nimbus/volume/up_axis.hpp"
#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using namespace nimbus::volume;
using nimbus::test::TempDir;

std::string up_axis_of(const Metadata& meta) {
  for (const auto& [key, value] : meta)
    if (key == "up_axis") return std::get<std::string>(value);
  return "";
}

openvdb::FloatGrid::Ptr one_voxel(const openvdb::Coord& at, float value, double voxel_size) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->tree().setValueOn(at, value);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_size));
  return grid;
}

TEST(VolumeIoUpAxis, YUpMovesWorldOneTwoThreeToOneThreeMinusTwo) {
  TempDir dir;
  ExportInfo info;
  info.up_axis = 'y';
  write_volume_vdb(dir / "y.vdb", {one_voxel({1, 2, 3}, 0.75f, 1.0)}, info);
  const VolumeFile f = read_volume_vdb(dir / "y.vdb");
  ASSERT_EQ(f.grid->activeVoxelCount(), 1u);
  const auto it = f.grid->cbeginValueOn();
  EXPECT_EQ(it.getCoord(), openvdb::Coord(1, 3, -2));
  EXPECT_EQ(*it, 0.75f);
  EXPECT_EQ(f.grid->transform().indexToWorld(it.getCoord()), openvdb::Vec3d(1, 3, -2));
  EXPECT_EQ(f.grid->voxelSize(), openvdb::Vec3d(1, 1, 1));
  EXPECT_EQ(up_axis_of(f.metadata), "y");
}

TEST(VolumeIoUpAxis, ZUpLeavesTheVoxelWhereItIs) {
  TempDir dir;
  write_volume_vdb(dir / "z.vdb", {one_voxel({1, 2, 3}, 0.75f, 1.0)}, ExportInfo{});
  const VolumeFile f = read_volume_vdb(dir / "z.vdb");
  ASSERT_EQ(f.grid->activeVoxelCount(), 1u);
  EXPECT_EQ(f.grid->cbeginValueOn().getCoord(), openvdb::Coord(1, 2, 3));
  EXPECT_EQ(up_axis_of(f.metadata), "z");
}

TEST(VolumeIoUpAxis, RotationIsProperAndKeepsWorldPositionsUnderAnyLinearTransform) {
  // Voxel size 0.5 with a translation: every voxel's world centre p lands at R p.
  auto grid = nimbus::test::make_ball(5, 0.5);
  grid->transform().postTranslate(openvdb::Vec3d(10.0, -3.0, 7.25));
  const auto rotated = rotate_z_up_to_y_up(*grid);
  EXPECT_EQ(rotated->activeVoxelCount(), grid->activeVoxelCount());
  EXPECT_EQ(rotated->voxelSize(), grid->voxelSize());
  EXPECT_TRUE(rotated->transform().isLinear());
  auto racc = rotated->getConstAccessor();
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    const openvdb::Vec3d p = grid->transform().indexToWorld(it.getCoord());
    const openvdb::Vec3d q(p.x(), p.z(), -p.y());
    const openvdb::Coord c = rotated->transform().worldToIndexCellCentered(q);
    ASSERT_TRUE(racc.isValueOn(c)) << it.getCoord();
    ASSERT_EQ(racc.getValue(c), *it);
    ASSERT_LT((rotated->transform().indexToWorld(c) - q).length(), 1e-12);
  }
  // Proper rotation: the right-handed frame stays right-handed (x cross y = z after mapping).
  const openvdb::Mat3d m = rotated->transform().baseMap()->getAffineMap()->getMat4().getMat3();
  EXPECT_GT(m.det(), 0.0);
  // And back again, exactly.
  const auto back = rotate_y_up_to_z_up(*rotated);
  EXPECT_EQ(back->transform(), grid->transform());
  auto bacc = back->getConstAccessor();
  EXPECT_EQ(back->activeVoxelCount(), grid->activeVoxelCount());
  for (auto it = grid->cbeginValueOn(); it; ++it) ASSERT_EQ(bacc.getValue(it.getCoord()), *it);
}

TEST(VolumeIoUpAxis, ActiveTilesRotateWithoutLosingVoxels) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->tree().fill(openvdb::CoordBBox({0, 0, 0}, {127, 127, 127}), 0.5f, true);  // one level-1 tile
  grid->tree().setValueOn(openvdb::Coord(200, 3, 4), 2.0f);
  ASSERT_GT(grid->tree().activeTileCount(), 0u);
  const auto rotated = rotate_z_up_to_y_up(*grid);
  EXPECT_EQ(rotated->activeVoxelCount(), grid->activeVoxelCount());
  EXPECT_EQ(rotated->tree().getValue(openvdb::Coord(200, 4, -3)), 2.0f);
  EXPECT_EQ(rotated->tree().getValue(openvdb::Coord(5, 127, -127)), 0.5f);
  EXPECT_EQ(rotated->evalActiveVoxelBoundingBox(), openvdb::CoordBBox({0, 0, -127}, {200, 127, 0}));
}

TEST(VolumeIoUpAxis, BadUpAxisIsRefused) {
  TempDir dir;
  ExportInfo info;
  info.up_axis = 'x';
  EXPECT_THROW(write_volume_vdb(dir / "x.vdb", {one_voxel({0, 0, 0}, 1.0f, 1.0)}, info), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.vdb"));
}

}  // namespace

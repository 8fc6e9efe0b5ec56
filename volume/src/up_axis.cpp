// Quarter-turn rotations of grids between Z-up and Y-up, voxel by voxel (exact, no resampling).
#include "nimbus/volume/up_axis.hpp"

#include <array>
#include <stdexcept>

namespace nimbus::volume {
namespace {

using Rot = std::array<std::array<int, 3>, 3>;  // column convention: p' = R p

openvdb::Coord rotated(const Rot& r, const openvdb::Coord& c) {
  openvdb::Coord out;
  for (int row = 0; row < 3; ++row) out[row] = r[row][0] * c[0] + r[row][1] * c[1] + r[row][2] * c[2];
  return out;
}

openvdb::CoordBBox rotated(const Rot& r, const openvdb::CoordBBox& box) {
  const openvdb::Coord a = rotated(r, box.min()), b = rotated(r, box.max());
  return {openvdb::Coord::minComponent(a, b), openvdb::Coord::maxComponent(a, b)};
}

// OpenVDB matrices act on row vectors (world = [i j k 1] * M), so with R as a column-convention
// rotation, index' = R index and world' = R world give M' = R4 * M * R4^T.
openvdb::math::Transform::Ptr rotate_transform(const Rot& r, const openvdb::math::Transform& t,
                                               const std::string& grid_name) {
  if (!t.isLinear())
    throw std::invalid_argument("grid " + grid_name + ": only a linear transform can change its up axis");
  const openvdb::Mat4d m = t.baseMap()->getAffineMap()->getMat4();
  openvdb::Mat4d r4 = openvdb::Mat4d::identity();
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) r4(row, col) = r[row][col];
  // Products with 0 and +-1 are exact, so the rotated map simplifies back to scale + translate.
  return openvdb::math::Transform::createLinearTransform(r4 * m * r4.transpose());
}

openvdb::FloatGrid::Ptr rotate(const openvdb::FloatGrid& grid, const Rot& r) {
  auto out = openvdb::FloatGrid::create(grid.background());
  static_cast<openvdb::MetaMap&>(*out) = static_cast<const openvdb::MetaMap&>(grid);
  out->setTransform(rotate_transform(r, grid.transform(), grid.getName()));
  auto& tree = out->tree();
  auto acc = out->getAccessor();
  const float bg = grid.background();
  for (auto it = grid.tree().cbeginValueAll(); it; ++it) {
    const bool on = it.isValueOn();
    if (!on && *it == bg) continue;  // the background is implicit
    if (it.isVoxelValue()) {
      acc.setValue(rotated(r, it.getCoord()), *it);
      if (!on) acc.setValueOff(rotated(r, it.getCoord()));
    } else {
      // A rotated tile box is shifted by one voxel against the node grid (-j maps [0, n) to
      // (-n, 0]), so fill() stores it as tiles one level down, never voxel by voxel.
      tree.fill(rotated(r, it.getBoundingBox()), *it, on);
    }
  }
  return out;
}

}  // namespace

openvdb::FloatGrid::Ptr rotate_z_up_to_y_up(const openvdb::FloatGrid& grid) {
  return rotate(grid, Rot{{{1, 0, 0}, {0, 0, 1}, {0, -1, 0}}});  // (x, y, z) -> (x, z, -y)
}

openvdb::FloatGrid::Ptr rotate_y_up_to_z_up(const openvdb::FloatGrid& grid) {
  return rotate(grid, Rot{{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}});  // (x, y, z) -> (x, -z, y)
}

}  // namespace nimbus::volume

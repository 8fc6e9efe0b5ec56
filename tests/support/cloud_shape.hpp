// Shape measures of one generated cloud, to tell a genus by its shape: its bodies
// (6-connected sets of cloud voxels), the flatness of its base and the widths of its layers. A
// cloud voxel has extinction at least kCloudExtinctionPerM (0.01 per metre, an optical depth of
// 1 over 100 m: what an observer sees as cloud rather than haze). Test code: the product does
// not measure its own shapes.
#pragma once
#include <openvdb/openvdb.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace nimbus::test {

inline constexpr double kCloudExtinctionPerM = 0.01;

// The cloud voxels of a density grid in a dense box (index space, z up), x fastest.
struct CloudMask {
  openvdb::Coord min{0};   // index of mask voxel (0, 0, 0)
  int nx = 0, ny = 0, nz = 0;
  double voxel_m = 0;
  std::vector<uint8_t> cloud;  // 1 where density * extinction_per_m >= kCloudExtinctionPerM
  size_t index(int i, int j, int k) const { return (size_t(k) * size_t(ny) + size_t(j)) * size_t(nx) + size_t(i); }
};

// Throws std::invalid_argument for a non-positive extinction, a grid that is not a uniform
// scale, or a box of more than 2^31 voxels (refused before allocating).
CloudMask cloud_mask(const openvdb::FloatGrid& density, double extinction_per_m);

// 6-connected bodies of the mask's cloud voxels.
struct Bodies {
  std::vector<int32_t> label;   // per mask voxel: -1 for no cloud, else the body's number
  std::vector<size_t> voxels;   // per body, its voxel count, largest first
  size_t total = 0;             // cloud voxels in all
  double largest_share() const { return total ? double(voxels.empty() ? 0 : voxels[0]) / double(total) : 0.0; }
};
// Numbers bodies by size (0: the largest). An iterative fill (no recursion).
Bodies cloud_bodies(const CloudMask& m);

// The base of one body: over the interior of its footprint (the columns holding any of its
// voxels, less the outer ring of width 0.25 times the footprint's equivalent radius, at least one
// column), the altitude of each column's lowest voxel of the body.
struct BaseFlatness {
  double depth_m = 0;        // (highest voxel - lowest voxel + 1) * voxel
  int lowest_layer = 0;      // the body's lowest voxel's layer in the mask (k)
  double base_iqr_m = 0;     // interquartile range of the columns' base altitude
  size_t interior_columns = 0;
  size_t footprint_columns = 0;
};
BaseFlatness base_flatness(const CloudMask& m, const Bodies& b, int32_t body);

// Widths of one body by layer: a layer's width is the larger of the x and y extents (metres)
// of the body's voxels in that layer. Tower: the median width over the layers from 10 % to
// 50 % of the body's depth above its base; anvil: the widest layer in its top 30 %.
struct TowerAndAnvil {
  double tower_width_m = 0;
  double anvil_width_m = 0;
  double ratio() const { return tower_width_m > 0 ? anvil_width_m / tower_width_m : 0.0; }
};
TowerAndAnvil tower_and_anvil(const CloudMask& m, const Bodies& b, int32_t body);

}  // namespace nimbus::test

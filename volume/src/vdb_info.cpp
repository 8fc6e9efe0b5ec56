// Grid-by-grid summaries of VDB files (for `nimbus info`).
#include "nimbus/volume/vdb_info.hpp"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <limits>
#include <sstream>

#include "vdb_common.hpp"
#include "vdb_isolated.hpp"
#include "vdb_open.hpp"

namespace nimbus::volume {
namespace {

using ScalarGrids = openvdb::TypeList<openvdb::FloatGrid, openvdb::DoubleGrid, openvdb::Int32Grid,
                                      openvdb::Int64Grid, openvdb::BoolGrid>;

GridSummary summarize(const openvdb::GridBase& grid) {
  GridSummary s;
  s.name = grid.getName();
  s.value_type = grid.valueType();
  s.grid_class = openvdb::GridBase::gridClassToString(grid.getGridClass());
  s.active_voxels = grid.activeVoxelCount();
  s.half_float = grid.saveFloatAsHalf();
  s.linear_transform = grid.transform().isLinear();
  const openvdb::Vec3d vs = grid.voxelSize();
  s.voxel_size = {vs[0], vs[1], vs[2]};
  s.metadata = detail::from_meta_map(grid);
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  s.empty = box.empty();
  if (!s.empty) {
    std::array<double, 3> lo, hi;
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    for (int corner = 0; corner < 8; ++corner) {
      const openvdb::Vec3d idx((corner & 1 ? box.max()[0] + 0.5 : box.min()[0] - 0.5),
                               (corner & 2 ? box.max()[1] + 0.5 : box.min()[1] - 0.5),
                               (corner & 4 ? box.max()[2] + 0.5 : box.min()[2] - 0.5));
      const openvdb::Vec3d w = grid.transform().indexToWorld(idx);
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], w[a]);
        hi[a] = std::max(hi[a], w[a]);
      }
    }
    for (int a = 0; a < 3; ++a) {
      s.index_min[a] = box.min()[a];
      s.index_max[a] = box.max()[a];
    }
    s.world_min = lo;
    s.world_max = hi;
  }
  // Background of any type, as OpenVDB prints it; value range of scalar grids.
  grid.apply<openvdb::GridTypes>([&](const auto& g) {
    std::ostringstream os;
    os << g.background();
    s.background = os.str();
  });
  grid.apply<ScalarGrids>([&](const auto& g) {
    bool any = false;
    double lo = 0, hi = 0;
    for (auto it = g.cbeginValueOn(); it; ++it) {
      const double v = double(*it);
      lo = any ? std::min(lo, v) : v;
      hi = any ? std::max(hi, v) : v;
      any = true;
    }
    if (any) s.value_range = std::make_pair(lo, hi);
  });
  return s;
}

}  // namespace

FileSummary summarize_vdb(const std::filesystem::path& path, const std::optional<std::string>& grid,
                          const VdbReadLimits& limits) {
  detail::GridsRead r = detail::read_grids(path, {detail::GridRequest::Kind::Every, grid}, limits);
  FileSummary out;
  out.metadata = std::move(r.metadata);
  out.checksum_verified = r.checksum_verified;
  for (const openvdb::GridBase::Ptr& g : r.read) out.grids.push_back(summarize(*g));
  return out;
}

}  // namespace nimbus::volume

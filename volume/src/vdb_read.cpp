// Reading a fog volume's float grid from a VDB file, and its dense active box.
#include "nimbus/volume/vdb_read.hpp"

#include <openvdb/tools/Dense.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "nimbus/base/memory.hpp"
#include "vdb_open.hpp"

namespace nimbus::volume {

VolumeFile read_volume_vdb(const std::filesystem::path& path, const std::optional<std::string>& grid_name) {
  const std::string file = path.string();
  detail::OpenedVdb vdb = detail::open_vdb(path);
  const std::string float_type = openvdb::typeNameAsString<float>();
  std::string chosen;
  if (grid_name) {
    bool found = false, is_float = false;
    for (const GridInfo& g : vdb.grids)
      if (g.name == *grid_name) {
        found = true;
        is_float |= g.value_type == float_type;
      }
    if (!found)
      throw GridNotFound(file + ": no grid named '" + *grid_name + "' (grids: " + detail::list_grids(vdb.grids) + ")");
    if (!is_float)
      throw std::runtime_error(file + ": grid '" + *grid_name + "' does not hold float values (grids: " +
                               detail::list_grids(vdb.grids) + ")");
    chosen = *grid_name;
  } else {
    for (const GridInfo& g : vdb.grids)
      if (g.value_type == float_type && (chosen.empty() || g.name == "density")) {
        chosen = g.name;
        if (chosen == "density") break;
      }
    if (chosen.empty() && !std::any_of(vdb.grids.begin(), vdb.grids.end(),
                                       [&](const GridInfo& g) { return g.value_type == float_type; }))
      throw std::runtime_error(file + ": no float grid to read (grids: " + detail::list_grids(vdb.grids) + ")");
  }

  VolumeFile out;
  out.grid = openvdb::gridPtrCast<openvdb::FloatGrid>(detail::read_grid(vdb, path, chosen));
  if (!out.grid) throw std::runtime_error(file + ": grid '" + chosen + "' is not a float grid");
  for (auto it = out.grid->cbeginValueOn(); it; ++it)
    if (!std::isfinite(*it))
      throw std::runtime_error(file + ": grid '" + chosen + "' holds non-finite values (corrupt file?)");
  out.metadata = std::move(vdb.metadata);
  out.grids = std::move(vdb.grids);
  out.checksum_verified = vdb.checksum_verified;
  return out;
}

DenseBox dense_active_box(const openvdb::FloatGrid& grid) {
  return dense_box(grid, grid.evalActiveVoxelBoundingBox());
}

DenseBox dense_box(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& bbox) {
  DenseBox box;
  if (bbox.empty()) return box;
  uint64_t count = 1;
  bool overflow = false;
  for (int a = 0; a < 3; ++a) {
    box.origin[a] = bbox.min()[a];
    box.size[a] = int64_t(bbox.max()[a]) - bbox.min()[a] + 1;
    overflow |= __builtin_mul_overflow(count, uint64_t(box.size[a]), &count);
  }
  const std::string what = "a dense copy of grid '" + grid.getName() + "' (" + std::to_string(box.size[0]) +
                           " x " + std::to_string(box.size[1]) + " x " + std::to_string(box.size[2]) + " voxels)";
  if (overflow) throw OutOfMemoryRequest(what + " exceeds any memory");
  ensure_fits_in_memory(count, sizeof(float), what);
  box.values.resize(size_t(count));
  // LayoutXYZ is OpenVDB's x-fastest layout.
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(bbox, box.values.data());
  openvdb::tools::copyToDense(grid, dense);
  return box;
}

}  // namespace nimbus::volume

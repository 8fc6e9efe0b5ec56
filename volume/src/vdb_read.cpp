// Reading a fog volume's float grid from a VDB file, and its dense active box.
#include "nimbus/volume/vdb_read.hpp"
#include "nimbus/base/validate.hpp"

#include <openvdb/tools/Dense.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "nimbus/base/memory.hpp"
#include "vdb_common.hpp"
#include "vdb_isolated.hpp"
#include "vdb_open.hpp"

namespace nimbus::volume {

namespace {

// Index-to-world must be finite and keep three dimensions (a zero or repeated axis has no
// inverse, and every world-to-index lookup would be NaN).
void check_transform(const std::string& where, const openvdb::math::Transform& t) {
  if (!t.isLinear()) return;  // frustum maps: left to the caller (the renderer refuses them)
  const openvdb::Mat4d m = t.baseMap()->getAffineMap()->getMat4();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!std::isfinite(m(i, j))) throw std::runtime_error(where + " has a transform that is not finite");
  const openvdb::Vec3d vs = t.voxelSize();
  const double det = m.getMat3().det();
  if (!(std::abs(det) > 1e-300) || !(std::abs(det) >= 1e-12 * vs[0] * vs[1] * vs[2]))
    throw std::runtime_error(where + " has a degenerate transform (voxel size " + number_text(vs[0]) + " x " +
                             number_text(vs[1]) + " x " + number_text(vs[2]) + ", determinant " +
                             number_text(det) + ")");
}

}  // namespace

VolumeFile read_volume_vdb(const std::filesystem::path& path, const std::optional<std::string>& grid_name) {
  VdbReadOptions options;
  options.grid = grid_name;
  return read_volume_vdb(path, options);
}

VolumeFile read_volume_vdb(const std::filesystem::path& path, const VdbReadOptions& options) {
  const std::string file = path.string();
  detail::GridsRead r =
      detail::read_grids(path, {detail::GridRequest::Kind::OneFloat, options.grid}, options.limits);
  if (r.read.size() != 1 || !r.read[0]) throw std::runtime_error(file + ": the grid could not be read");
  const std::string where = detail::one_line(file + ": grid '" + r.read[0]->getName().substr(0, 200) + "'");
  VolumeFile out;
  out.grid = openvdb::gridPtrCast<openvdb::FloatGrid>(r.read[0]);
  if (!out.grid) throw std::runtime_error(where + " is not a float grid");
  try {
    check_transform(where, out.grid->transform());
  } catch (const openvdb::Exception& e) {  // ScaleMap::getAffineMap on zero, NaN or subnormal scales
    throw std::runtime_error(where + " has a transform OpenVDB cannot invert (" + detail::one_line(e.what()) + ")");
  }
  for (auto it = out.grid->cbeginValueAll(); it; ++it)  // tiles and voxels, active or not
    if (!std::isfinite(*it)) throw std::runtime_error(where + " holds non-finite values (corrupt file?)");
  if (!std::isfinite(out.grid->background())) throw std::runtime_error(where + " has a non-finite background");
  if (out.grid->getGridClass() == openvdb::GRID_LEVEL_SET) {
    if (!options.level_set_to_fog)
      throw std::runtime_error(where + " is a level set (a signed distance field), not a density; convert it to a "
                               "fog volume with --level-set-to-fog");
    openvdb::tools::sdfToFogVolume(*out.grid);
    out.from_level_set = true;
  }
  bool any = false;
  for (auto it = out.grid->cbeginValueOn(); it; ++it) {
    out.min_value = any ? std::min(out.min_value, *it) : *it;
    any = true;
    if (*it < 0.0f) out.negative_values += it.isVoxelValue() ? 1 : it.getVoxelCount();
  }
  out.metadata = std::move(r.metadata);
  out.grids = std::move(r.grids);
  out.checksum_verified = r.checksum_verified;
  out.read_in_child = r.read_in_child;
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
  const std::string what = detail::one_line("a dense copy of grid '" + grid.getName().substr(0, 200) + "' (" +
                                            std::to_string(box.size[0]) + " x " + std::to_string(box.size[1]) + " x " +
                                            std::to_string(box.size[2]) + " voxels)");
  if (overflow) throw OutOfMemoryRequest(what + " exceeds any memory");
  // OpenVDB's copyToDense adds node sizes to node origins in int32: near the ends of the index
  // range that overflows (a crash), and an axis longer than 2^31 - 1 has no Coord to index it.
  constexpr int32_t kIndexLimit = int32_t(1) << 30;
  for (int a = 0; a < 3; ++a) {
    const std::string axis(1, char('x' + a));
    if (box.size[a] > std::numeric_limits<int32_t>::max())
      throw std::runtime_error(what + " spans more than 2^31 - 1 voxels along " + axis + ", more than a dense copy can index");
    if (bbox.min()[a] < -kIndexLimit || bbox.max()[a] > kIndexLimit)
      throw std::runtime_error(what + " reaches index " + std::to_string(bbox.min()[a] < -kIndexLimit ? bbox.min()[a] : bbox.max()[a]) +
                               " along " + axis + ", beyond +-2^30, where a dense copy cannot index it");
  }
  ensure_fits_in_memory(count, sizeof(float), what);
  box.values.resize(size_t(count));
  // LayoutXYZ is OpenVDB's x-fastest layout.
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(bbox, box.values.data());
  openvdb::tools::copyToDense(grid, dense);
  return box;
}

openvdb::FloatGrid::Ptr grid_from_dense_box(const DenseBox& box, const openvdb::math::Transform& transform,
                                            const std::string& name) {
  uint64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    if (box.size[a] < 0 || box.size[a] > std::numeric_limits<int32_t>::max())
      throw std::invalid_argument("grid " + name + ": size along " + std::string(1, char('x' + a)) + " out of range");
    count *= uint64_t(box.size[a]);
  }
  if (box.values.size() != count)
    throw std::invalid_argument("grid " + name + ": " + std::to_string(box.values.size()) + " values for " +
                                std::to_string(count) + " voxels");
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(name);
  grid->setTransform(transform.copy());
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  if (count == 0) return grid;
  const openvdb::Coord lo(box.origin[0], box.origin[1], box.origin[2]);
  const openvdb::Coord hi(int32_t(box.origin[0] + box.size[0] - 1), int32_t(box.origin[1] + box.size[1] - 1),
                          int32_t(box.origin[2] + box.size[2] - 1));
  // LayoutXYZ is OpenVDB's x-fastest layout; the view only reads the values. Tolerance 0: a voxel
  // equal to the background (0) stays inactive, as a fog volume's empty space is.
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(openvdb::CoordBBox(lo, hi),
                                                               const_cast<float*>(box.values.data()));
  openvdb::tools::copyFromDense(dense, *grid, 0.0f);
  return grid;
}

}  // namespace nimbus::volume

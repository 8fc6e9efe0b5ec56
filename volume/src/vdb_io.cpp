// OpenVDB output of dense sample grids, and the sealed, atomic file write every writer uses.
#include "nimbus/volume/vdb_io.hpp"

#include <openvdb/tools/Dense.h>

#include <cmath>
#include <stdexcept>

#include "nimbus/base/atomic_file.hpp"
#include "vdb_common.hpp"
#include "vdb_seal.hpp"

namespace nimbus::volume {

const char* library_version() { return NIMBUS_VERSION; }

namespace detail {

void write_sealed_vdb(const std::filesystem::path& path, const openvdb::GridCPtrVec& grids,
                      openvdb::MetaMap meta) {
  init_openvdb();
  if (meta[kChecksumKey]) meta.removeMeta(kChecksumKey);
  meta.insertMeta(kChecksumKey, openvdb::StringMetadata(checksum_placeholder()));
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::string uuid;
    try {
      openvdb::io::File file(tmp.string());
      file.write(grids, meta);  // the library's default compression: Blosc + active mask
      uuid = file.getUniqueTag();
      file.close();
    } catch (const std::exception& e) {
      throw std::runtime_error("cannot write " + path.string() + ": " + one_line(e.what()));
    }
    seal_vdb_file(tmp, uuid, path);
  });
}

}  // namespace detail

void write_dense_vdb(const std::filesystem::path& path, const DenseGridDesc& desc,
                     std::span<const float> values) {
  detail::init_openvdb();
  const int64_t count = desc.res[0] * desc.res[1] * desc.res[2];
  if (static_cast<int64_t>(values.size()) != count)
    throw std::invalid_argument("grid " + desc.name + ": value count does not match resolution");
  for (int a = 0; a < 3; ++a)
    if (desc.res[a] < 1 || desc.res[a] > (int64_t(1) << 30))
      throw std::invalid_argument("grid " + desc.name + ": resolution out of range");
  if (!std::isfinite(desc.voxel_size) || desc.voxel_size <= 0.0)
    throw std::invalid_argument("grid " + desc.name + ": voxel size must be finite and > 0");
  for (int64_t i = 0; i < count; ++i)
    if (!std::isfinite(values[i]))
      throw std::invalid_argument("grid " + desc.name + ": non-finite sample at index " + std::to_string(i));

  auto grid = openvdb::FloatGrid::create(0.0f);
  const openvdb::CoordBBox box(openvdb::Coord(0, 0, 0),
                               openvdb::Coord(int(desc.res[0] - 1), int(desc.res[1] - 1), int(desc.res[2] - 1)));
  // OpenVDB's LayoutXYZ is the x-fastest layout (offset = i + j*nx + k*nx*ny); the dense view
  // only reads the samples.
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, const_cast<float*>(values.data()));
  // A negative tolerance keeps every voxel active, even those equal to the background.
  openvdb::tools::copyFromDense(dense, *grid, -1.0f);
  grid->setName(desc.name);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(desc.voxel_size));
  grid->setGridClass(desc.grid_class == GridClass::FogVolume ? openvdb::GRID_FOG_VOLUME
                                                              : openvdb::GRID_UNKNOWN);
  grid->setSaveFloatAsHalf(desc.half_float);
  detail::write_sealed_vdb(path, {grid}, detail::to_meta_map(desc.metadata));
}

}  // namespace nimbus::volume

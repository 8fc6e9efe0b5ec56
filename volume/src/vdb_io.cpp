// OpenVDB output of dense grids.
#include "nimbus/volume/vdb_io.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <cmath>
#include <mutex>
#include <stdexcept>

#include "nimbus/volume/atomic_file.hpp"

namespace nimbus::volume {
namespace {
void init_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}
}  // namespace

void write_dense_vdb(const std::filesystem::path& path, const DenseGridDesc& desc,
                     std::span<const float> values) {
  init_openvdb();
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

  openvdb::MetaMap meta;
  for (const auto& [key, value] : desc.metadata) {
    if (const auto* s = std::get_if<std::string>(&value)) meta.insertMeta(key, openvdb::StringMetadata(*s));
    else if (const auto* d = std::get_if<double>(&value)) meta.insertMeta(key, openvdb::DoubleMetadata(*d));
    else meta.insertMeta(key, openvdb::Int64Metadata(std::get<int64_t>(value)));
  }
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    openvdb::io::File file(tmp.string());
    file.write({grid}, meta);
    file.close();
  });
}

}  // namespace nimbus::volume

// A sky's clouds as one density grid (sky_volume.hpp).
#include "nimbus/volume/sky_volume.hpp"

#include <openvdb/tools/Composite.h>

#include <stdexcept>

#include "nimbus/base/memory.hpp"

namespace nimbus::volume {
namespace {

void refuse_file_clouds(const Sky& sky) {
  for (std::size_t i = 0; i < sky.clouds.size(); ++i)
    if (!sky.clouds[i].file.empty())
      throw std::invalid_argument("sky clouds[" + std::to_string(i) + "] is a file cloud ('" + sky.clouds[i].file +
                                  "'): a sky volume holds preset clouds only; leave the file out of this sky, and "
                                  "place the file beside the written volume in the host");
}

}  // namespace

glm::dvec3 sky_cloud_origin(const Sky& sky, std::size_t index, double time_s) {
  return sky.clouds.at(index).position_m + sky.wind_m_s * time_s;
}

uint64_t sky_dense_voxels(const Sky& sky, double voxel_size_m, double time_s) {
  refuse_file_clouds(sky);
  uint64_t total = 0;
  for (std::size_t i = 0; i < sky.clouds.size(); ++i) {
    const openvdb::CoordBBox box =
        density_index_box(sky_cloud_params(sky, i), voxel_size_m, time_s, sky_cloud_origin(sky, i, time_s));
    if (box.empty()) continue;
    const openvdb::Coord n = box.dim();
    total += uint64_t(n.x()) * uint64_t(n.y()) * uint64_t(n.z());
  }
  return total;
}

openvdb::FloatGrid::Ptr generate_sky_density(const Sky& sky, double voxel_size_m, double time_s, SkyVolumeStats* stats) {
  validate(sky);
  const uint64_t dense = sky_dense_voxels(sky, voxel_size_m, time_s);
  ensure_fits_in_memory(dense, sizeof(float), "the sky's clouds' bounding boxes at this voxel size");
  openvdb::FloatGrid::Ptr sum;
  for (std::size_t i = 0; i < sky.clouds.size(); ++i) {
    GenerateOptions o;
    o.voxel_size = voxel_size_m;
    o.time = time_s;  // the evolution; the sky clouds' own wind is 0, the drift is in the origin
    o.origin_m = sky_cloud_origin(sky, i, time_s);
    openvdb::FloatGrid::Ptr g = generate_density(sky_cloud_params(sky, i), o);
    if (!sum) {
      sum = g;
    } else {
      openvdb::tools::compSum(*sum, *g);  // densities add where clouds overlap (see the header)
    }
  }
  if (stats) {
    stats->clouds = int(sky.clouds.size());
    stats->active_voxels = int64_t(sum->activeVoxelCount());
    stats->dense_voxels = dense;
  }
  return sum;
}

}  // namespace nimbus::volume

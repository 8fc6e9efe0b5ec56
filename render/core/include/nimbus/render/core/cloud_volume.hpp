// A cloud to render: the dense active box of a density grid, its index-to-world transform and
// its optics, with the trilinear density lookup that both the GPU slicer (border 0 texture) and
// the CPU reference see: OpenVDB's BoxSampler over the grid, 0 outside the active box.
#pragma once
#include <openvdb/openvdb.h>

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::render {

struct CloudVolume {
  std::string name;                 // preset or file name, for metadata and messages
  volume::DenseBox box;             // density per voxel, x fastest
  glm::dmat4 index_to_world{1.0};   // affine; voxel (i, j, k) is centred at index_to_world * (i, j, k, 1)
  glm::dmat4 world_to_index{1.0};
  openvdb::math::Transform::Ptr transform;  // the grid's own, for upload_volume
  CloudOptics optics;
  // World bounds of the support (density can be non-zero only inside): index origin - 1 to
  // origin + size on each axis, as VolumeTexture::world_min/max.
  glm::dvec3 world_min{0.0}, world_max{0.0};
};

// Copies the active box of `grid` (volume::dense_active_box). Throws std::invalid_argument
// naming `name` for an empty grid or a non-affine transform; OutOfMemoryRequest for a box too
// large to hold.
CloudVolume make_cloud_volume(const openvdb::FloatGrid& grid, const CloudOptics& optics, const std::string& name);

// Index coordinates (voxel centres at integers) to world metres through the grid's own transform.
glm::dvec3 index_to_world(const openvdb::math::Transform& transform, const glm::dvec3& index);

// The affine index-to-world map of a linear transform as a matrix: voxel (i, j, k) is centred
// at M * (i, j, k, 1). std::invalid_argument for a non-affine (frustum) transform.
glm::dmat4 index_to_world_matrix(const openvdb::math::Transform& transform);

// Trilinear density at a world point (0 outside the support), in double precision.
double sample_density(const CloudVolume& cloud, const glm::dvec3& world_m);

// Union of the clouds' supports (world_min > world_max when the list is empty).
void cloud_bounds(const std::vector<CloudVolume>& clouds, glm::dvec3& world_min, glm::dvec3& world_max);

}  // namespace nimbus::render

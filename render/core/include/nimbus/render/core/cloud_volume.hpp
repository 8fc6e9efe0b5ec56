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
  // Evolution between keyframes: the next keyframe's density on the same box (origin and size;
  // empty: none) and its weight. The density is (1 - blend) box + blend next_box, trilinear in
  // each (set_next_keyframe).
  volume::DenseBox next_box;
  double blend = 0.0;  // [0, 1]
  // World bounds of the support (density can be non-zero only inside): index origin - 1 to
  // origin + size on each axis, as VolumeTexture::world_min/max.
  glm::dvec3 world_min{0.0}, world_max{0.0};
  // A tile of a periodic field (docs/volume.md, "Periodic fields"): the density repeats with this
  // period along render x and z (the world's x and y), metres; 0 on an axis: it does not repeat
  // there, and y is always 0. The slicer draws copies of the tile out to
  // CloudSliceSettings::repeat_to_m (cloud_tiles.hpp); nothing else reads it.
  glm::dvec3 period_m{0.0};
};

// Copies the active box of `grid` (volume::dense_active_box). Throws std::invalid_argument
// naming `name` for an empty grid or a non-affine transform; OutOfMemoryRequest for a box too
// large to hold.
CloudVolume make_cloud_volume(const openvdb::FloatGrid& grid, const CloudOptics& optics, const std::string& name);

// The same from a box of density already copied out of a grid (volume::dense_box) and the
// grid's transform. Same errors.
CloudVolume make_cloud_volume(volume::DenseBox box, const openvdb::math::Transform& transform,
                              const CloudOptics& optics, const std::string& name);

// Gives `cloud` a next keyframe to blend towards. Throws std::invalid_argument naming the cloud
// when `next` is not on the same box, or blend is outside [0, 1].
void set_next_keyframe(CloudVolume& cloud, volume::DenseBox next, double blend);

// Moves the cloud by `offset_m` (wind drift): the density field translates exactly, so nothing
// is resampled; every map, the bounds and the transform move together.
void translate(CloudVolume& cloud, const glm::dvec3& offset_m);

// Index coordinates (voxel centres at integers) to world metres through the grid's own transform.
glm::dvec3 index_to_world(const openvdb::math::Transform& transform, const glm::dvec3& index);

// The affine index-to-world map of a linear transform as a matrix: voxel (i, j, k) is centred
// at M * (i, j, k, 1). std::invalid_argument for a non-affine (frustum) transform.
glm::dmat4 index_to_world_matrix(const openvdb::math::Transform& transform);

// How a cloud moves from where it was made, frame by frame, without new density: the wind's
// drift and the blend towards its next keyframe.
struct CloudMotion {
  glm::dvec3 offset_m{0.0};  // translation from the cloud's own placement, metres
  double blend = 0.0;        // [0, 1]; only for a cloud with a next keyframe
};

// `cloud` as `motion` moves it (translate, then blend). Throws std::invalid_argument naming the
// cloud for a blend outside [0, 1], or a non-zero blend without a next keyframe.
void apply_motion(CloudVolume& cloud, const CloudMotion& motion);

// Trilinear density at a world point (0 outside the support), blended towards the next keyframe,
// in double precision.
double sample_density(const CloudVolume& cloud, const glm::dvec3& world_m);

// The same at box-local index coordinates (world_to_index minus the box origin: voxel centres
// at 0 .. size - 1), for callers that march in index space.
double sample_density_local(const CloudVolume& cloud, const glm::dvec3& local);

// Union of the clouds' supports (world_min > world_max when the list is empty).
void cloud_bounds(const std::vector<CloudVolume>& clouds, glm::dvec3& world_min, glm::dvec3& world_max);

}  // namespace nimbus::render

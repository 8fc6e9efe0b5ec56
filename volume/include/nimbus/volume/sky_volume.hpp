// A sky's clouds as one density grid (`nimbus generate --sky`), for Blender or Houdini: every
// preset cloud generated at the sky's time and placed as the viewer places it, at its position
// moved by the sky's wind * time (the drift) with its noise evolved by time * its evolution rate,
// all on one voxel grid. Overlapping clouds add: extinction coefficients of media that share a
// volume add (sigma_t = sum of the parts' sigma_t; Pharr, Jakob & Humphreys 2023, "Physically
// Based Rendering", 4th ed., section 11.1), and density is extinction per unit sigma_t.
#pragma once
#include <openvdb/openvdb.h>

#include <cstdint>

#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/sky.hpp"

namespace nimbus::volume {

struct SkyVolumeStats {
  int clouds = 0;
  int64_t active_voxels = 0;
  uint64_t dense_voxels = 0;  // the clouds' index boxes, summed: the most the grids could hold
};

// Where cloud `index` of the sky goes at `time_s`: its position plus the wind's drift.
glm::dvec3 sky_cloud_origin(const Sky& sky, std::size_t index, double time_s);

// The clouds' index boxes summed, in voxels (std::invalid_argument naming the cloud for a file
// cloud, which this writer refuses: a VDB of another tool is not regenerated here).
uint64_t sky_dense_voxels(const Sky& sky, double voxel_size_m, double time_s);

// Checks memory first (nimbus::OutOfMemoryRequest naming the sky's boxes), then generates every
// cloud and sums them into one "density" fog volume grid.
openvdb::FloatGrid::Ptr generate_sky_density(const Sky& sky, double voxel_size_m, double time_s,
                                             SkyVolumeStats* stats = nullptr);

}  // namespace nimbus::volume

// A plane-parallel slab as a cloud, for the transport tests (the path tracer, the light volume):
// n x layers x n voxels of 1 m, density 1, of total optical thickness tau (trilinear ramps at its
// faces, one voxel beyond each, change the profile, not the total).
#pragma once
#include <openvdb/openvdb.h>

#include "nimbus/render/core/cloud_volume.hpp"

namespace nimbus::render::test {

inline CloudVolume slab(double tau, int layers, int n, const Phase& phase, double albedo) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(1.0));
  grid->fill(openvdb::CoordBBox(openvdb::Coord(0, 0, 0), openvdb::Coord(n - 1, layers - 1, n - 1)), 1.0f, true);
  grid->tree().voxelizeActiveTiles();
  CloudOptics o;
  o.extinction_per_m = tau / layers;
  o.albedo = glm::dvec3(albedo);
  o.phase = phase;
  return make_cloud_volume(*grid, o, "slab");
}

}  // namespace nimbus::render::test

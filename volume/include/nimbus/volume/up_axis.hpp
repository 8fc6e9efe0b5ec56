// Up-axis conversion of grids. nimbus works Z-up (Blender's convention); Houdini, Maya and
// vdb_render expect +Y up, and VDB files have no up-axis field, so a Y-up export rotates the
// grids themselves.
#pragma once
#include <openvdb/openvdb.h>

namespace nimbus::volume {

// The proper rotation (x, y, z) -> (x, z, -y): world +Z becomes +Y and nothing is mirrored
// (determinant +1). It is a quarter turn, so voxels move exactly: voxel (i, j, k) becomes
// voxel (i, k, -j) and the transform T becomes R T R^-1, which keeps the voxel size. Every
// stored value moves, active or inactive, tiles included; metadata is copied. Throws
// std::invalid_argument naming the grid for a non-linear (frustum) transform.
openvdb::FloatGrid::Ptr rotate_z_up_to_y_up(const openvdb::FloatGrid& grid);

// The inverse, (x, y, z) -> (x, -z, y): brings a Y-up file (Houdini's) into nimbus's Z-up.
openvdb::FloatGrid::Ptr rotate_y_up_to_z_up(const openvdb::FloatGrid& grid);

}  // namespace nimbus::volume

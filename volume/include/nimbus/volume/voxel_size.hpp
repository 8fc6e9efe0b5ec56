// The voxel sizes nimbus makes and takes, in metres: one range for `generate --voxel-size`, a
// Volume made from an array (Python) and the module's voxel_size arguments.
#pragma once
#include <string>

namespace nimbus::volume {

// From a micrometre (a lab's steam at the finest) to a thousand kilometres (a whole sky in one
// voxel): outside it a voxel's volume, size^3, leaves the range where OpenVDB can invert the
// transform (it refuses a determinant below 1e-300 as "Non-zero scale values required") or where
// a grid's world extent stays within the renderer's 1e8 m.
inline constexpr double kMinVoxelSize_m = 1e-6;
inline constexpr double kMaxVoxelSize_m = 1e6;

// Throws std::invalid_argument "<what>: must be within [1e-06, 1e+06] metres, got <v>" (as %g)
// for a voxel size outside the range or not finite.
void check_voxel_size(double size_m, const std::string& what);

}  // namespace nimbus::volume

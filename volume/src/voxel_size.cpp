// The range of voxel sizes (voxel_size.hpp).
#include "nimbus/volume/voxel_size.hpp"

#include <cmath>
#include <stdexcept>

#include "nimbus/base/validate.hpp"

namespace nimbus::volume {

void check_voxel_size(double size_m, const std::string& what) {
  if (std::isfinite(size_m) && size_m >= kMinVoxelSize_m && size_m <= kMaxVoxelSize_m) return;
  throw std::invalid_argument(what + ": must be within [" + number_text(kMinVoxelSize_m) + ", " +
                              number_text(kMaxVoxelSize_m) + "] metres, got " + number_text(size_m));
}

}  // namespace nimbus::volume

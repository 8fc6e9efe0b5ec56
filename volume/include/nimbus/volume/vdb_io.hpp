// Dense sample grids written as OpenVDB files that any VDB tool reads.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace nimbus::volume {

using MetaValue = std::variant<std::string, double, int64_t>;
using Metadata = std::vector<std::pair<std::string, MetaValue>>;

enum class GridClass { Unknown, FogVolume };

struct DenseGridDesc {
  std::string name = "density";
  std::array<int64_t, 3> res{1, 1, 1};  // x fastest in the value array
  double voxel_size = 1.0;              // world units per voxel
  GridClass grid_class = GridClass::Unknown;
  bool half_float = false;              // save values as 16-bit floats
  Metadata metadata;                    // file-level metadata
};

// Writes every sample as an active voxel at index (i, j, k), atomically. Throws
// std::invalid_argument for non-finite samples or a size mismatch, std::runtime_error for
// I/O failures.
void write_dense_vdb(const std::filesystem::path& path, const DenseGridDesc& desc,
                     std::span<const float> values);

}  // namespace nimbus::volume

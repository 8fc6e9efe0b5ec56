// What a VDB file holds, grid by grid, for `nimbus info`: any grid type, not only float.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::volume {

struct GridSummary {
  std::string name;
  std::string value_type;   // "float", "int32", "vec3s"...
  std::string grid_class;   // OpenVDB's name: "fog volume", "level set", "unknown"...
  uint64_t active_voxels = 0;
  bool empty = true;        // no active values; the boxes below are then all 0
  std::array<int32_t, 3> index_min{}, index_max{};  // active voxel bounding box, inclusive
  std::array<double, 3> world_min{}, world_max{};   // its extent in world space: the box of the
                                                    // voxels' corners, (index -+ 0.5) transformed
  std::array<double, 3> voxel_size{};
  bool linear_transform = true;
  std::optional<std::pair<double, double>> value_range;  // scalar grids with active values
  std::string background;   // as OpenVDB prints the value
  bool half_float = false;  // is_saved_as_half_float
  Metadata metadata;        // the grid's own metadata (class, creator, file_* ...)
};

struct FileSummary {
  std::vector<GridSummary> grids;  // as OpenVDB lists them (by name)
  Metadata metadata;               // file-level
  bool checksum_verified = false;  // nimbus's seal present and intact
};

// Reads the whole file (or only `grid`, GridNotFound when absent); a foreign file in the
// isolated child (vdb_read.hpp). Errors as in vdb_read.hpp.
FileSummary summarize_vdb(const std::filesystem::path& path,
                          const std::optional<std::string>& grid = std::nullopt, const VdbReadLimits& limits = {});

}  // namespace nimbus::volume

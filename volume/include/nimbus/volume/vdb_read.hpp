// Reading fog volumes from OpenVDB files written by nimbus or by anyone else (Houdini,
// Blender, EmberGen): a float grid by name with any transform, values above 1 allowed (real
// Houdini smoke reaches 5.7, research-ecosystem.md section 0), and a dense copy of its active
// box for the renderer.
//
// Every failure is a std::runtime_error whose one-line message starts with the file name:
// missing file, not a VDB file, truncated or corrupt file, no float grid, unknown grid name.
// Files nimbus wrote carry a CRC-32 seal (vdb_io.hpp) that is checked before OpenVDB parses
// any grid, so damage to them is always reported; for other files OpenVDB's own checks apply.
#pragma once
#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::volume {

// The file has no grid by the name asked for; the message lists the grids it has.
struct GridNotFound : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct GridInfo {
  std::string name;
  std::string value_type;  // OpenVDB's name: "float", "double", "int32", "vec3s"...
};

struct VolumeFile {
  openvdb::FloatGrid::Ptr grid;  // named as in the file; transform and class as stored
  Metadata metadata;             // the file-level metadata (nimbus's keys: vdb_io.hpp)
  std::vector<GridInfo> grids;   // every grid in the file, as OpenVDB lists them (by name)
  bool checksum_verified = false;  // the file carried nimbus's seal and it matched
};

// Reads one float grid: `grid_name` if given (GridNotFound when absent; std::runtime_error
// when it is not a float grid), else "density" if the file has a float grid of that name,
// else the first float grid as OpenVDB lists them (by name, as vdb_print and vdb_render do).
// Also rejects grids holding NaN or Inf in their active values.
VolumeFile read_volume_vdb(const std::filesystem::path& path,
                           const std::optional<std::string>& grid_name = std::nullopt);

// The active bounding box of a grid as a dense array, x fastest:
// values[(i - origin.x) + size.x * ((j - origin.y) + size.y * (k - origin.z))] is voxel
// (i, j, k). Inactive voxels inside the box hold their stored value (0 in a fog volume).
struct DenseBox {
  std::array<int32_t, 3> origin{0, 0, 0};  // index-space coordinates of values[0]
  std::array<int64_t, 3> size{0, 0, 0};    // voxels per axis; all 0 for an empty grid
  std::vector<float> values;
};

// Throws nimbus::OutOfMemoryRequest (before allocating) when the box would not fit in memory.
DenseBox dense_active_box(const openvdb::FloatGrid& grid);

// The grid's values over a given index box (voxels outside the grid's active ones hold the
// background), e.g. the same box for every keyframe of an evolving cloud. Empty box -> empty
// result. Same memory errors.
DenseBox dense_box(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& bbox);

}  // namespace nimbus::volume

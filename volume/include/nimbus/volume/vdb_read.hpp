// Reading fog volumes from OpenVDB files written by nimbus or by anyone else (Houdini,
// Blender, EmberGen): a float grid by name with any transform, values above 1 allowed (real
// Houdini smoke file, smoke.vdb of the mjurczyk/openvdb examples, reaches 5.71), and a dense copy of its active
// box for the renderer.
//
// Every failure is a std::runtime_error whose one-line message starts with the file name:
// missing file, not a regular file, not a VDB file, truncated or corrupt file, no float grid,
// unknown grid name, a level set, non-finite values, a degenerate transform.
//
// Files nimbus wrote carry a CRC-32 seal (vdb_io.hpp) that is checked before OpenVDB parses
// any grid, so damage to them is always reported, and they are read in this process. Any other
// file is foreign and untrusted: OpenVDB opens and reads it in a forked child process with a
// memory and time limit (VdbReadLimits), which hands the grids back; a crash, an absurd
// allocation or an endless loop inside OpenVDB becomes an error naming the file. (The seal is
// a check against damage, not a signature: a file forged to carry a valid seal is read here.)
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

// Limits of the child process that reads a foreign file. Over them, the read fails with an error
// naming the file and the limit.
struct VdbReadLimits {
  // Memory the child may take on top of what the process had; also the most its answer may
  // hold. 0: the environment's NIMBUS_READ_MEMORY_GB, else max(2 GiB, 64 x the file's size), at
  // most a third of the memory available.
  uint64_t memory_bytes = 0;
  // Wall-clock (and CPU) seconds. 0: the environment's NIMBUS_READ_SECONDS, else 20 s + 1 s per
  // 5 MB of file.
  double seconds = 0.0;
};

struct VdbReadOptions {
  std::optional<std::string> grid;  // see read_volume_vdb
  // A level set (a signed distance field, class GRID_LEVEL_SET) is refused as a density; with
  // this it becomes a fog volume instead (openvdb::tools::sdfToFogVolume: 1 inside, 0 outside,
  // a linear ramp across the inner half of the narrow band).
  bool level_set_to_fog = false;
  VdbReadLimits limits;
};

struct VolumeFile {
  openvdb::FloatGrid::Ptr grid;  // named as in the file; transform and class as stored
  Metadata metadata;             // the file-level metadata (nimbus's keys: vdb_io.hpp)
  std::vector<GridInfo> grids;   // every grid in the file, as OpenVDB lists them (by name)
  bool checksum_verified = false;  // the file carried nimbus's seal and it matched
  bool read_in_child = false;      // foreign: read by the isolated child process
  bool from_level_set = false;     // converted by VdbReadOptions::level_set_to_fog
  // Active values below 0, which a density cannot be (left as they are; callers report them).
  uint64_t negative_values = 0;
  float min_value = 0.0f;          // the least active value (0 for an empty grid)
};

// Reads one float grid: `grid` if given (GridNotFound when absent; std::runtime_error when it is
// not a float grid), else "density" if the file has a float grid of that name, else the first
// float grid as OpenVDB lists them (by name, as vdb_print and vdb_render do). Rejects grids
// holding NaN or Inf in their active values, level sets (unless converted), and transforms that
// are not finite or collapse a dimension.
VolumeFile read_volume_vdb(const std::filesystem::path& path, const VdbReadOptions& options);
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

// Throws nimbus::OutOfMemoryRequest (before allocating) when the box would not fit in memory,
// and std::runtime_error when it spans more voxels along an axis than a dense copy can index
// (2^31 - 1) or reaches beyond index +-2^30 (where OpenVDB's copy overflows int32).
DenseBox dense_active_box(const openvdb::FloatGrid& grid);

// The grid's values over a given index box (voxels outside the grid's active ones hold the
// background), e.g. the same box for every keyframe of an evolving cloud. Empty box -> empty
// result. Same memory errors.
DenseBox dense_box(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& bbox);

// The inverse: a fog grid named `name` with `transform` whose voxels are the box's; voxels equal
// to 0 stay inactive. std::invalid_argument when the sizes and the values do not agree.
openvdb::FloatGrid::Ptr grid_from_dense_box(const DenseBox& box, const openvdb::math::Transform& transform,
                                            const std::string& name = "density");

// Where the isolated reader program (nimbus-vdb-reader) is, for a caller that is not the nimbus
// program (the Python module keeps it in its package). Order of search: $NIMBUS_VDB_READER, this
// path, beside the running program, the build tree.
void set_vdb_reader_program(const std::filesystem::path& program);

}  // namespace nimbus::volume

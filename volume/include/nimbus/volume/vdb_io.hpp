// Writing OpenVDB files that Blender, Houdini and vdb_print read: dense sample grids (`nimbus
// noise`) and sparse density volumes with optional extra grids (temperature, flame) and the
// file metadata downstream tools look for (docs/volume.md, "Files, as downstream tools expect them").
//
// Every file is written atomically (atomic_file.hpp) and sealed with a whole-file CRC-32 that
// the reader (vdb_read.hpp) checks before it parses any grid; the header UUID is derived from
// the content, so the same grids and metadata always give the same bytes.
#pragma once
#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace nimbus::volume {

using MetaValue = std::variant<std::string, double, int64_t>;
using Metadata = std::vector<std::pair<std::string, MetaValue>>;

// The nimbus version this library was built as ("0.1.0").
const char* library_version();

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

// What a volume file says about itself, written as file-level metadata under the keys in
// the comments. VDB has no up-axis or units field, so these are informative for people and
// pipelines (Blender is Z-up and Houdini Y-up, both in metres).
struct ExportInfo {
  std::string creator;                 // "creator"; empty: "nimbus <version>"
  std::string preset;                  // "preset", e.g. "cumulus_humilis"
  int64_t seed = 0;                    // "seed"
  double time = 0.0;                   // "time", seconds
  int64_t frame = 0;                   // "frame"
  std::optional<double> fps;           // "fps", written only when set
  char up_axis = 'z';                  // "up_axis": 'z' (nimbus, Blender) or 'y' (Houdini)
  std::string units = "metres";        // "units": of the voxel size and the world positions
  std::string nimbus_version;          // "nimbus_version"; empty: library_version()
  Metadata extra;                      // more keys; none may repeat the keys above
};

struct ExportOptions {
  bool half_float = true;  // store values as 16-bit floats (about 28 % smaller with Blosc)
};

// The file metadata for `info`, in key order. Throws std::invalid_argument for an up axis
// other than 'y'/'z', a non-finite time, an fps that is not finite and > 0, empty units, or an
// extra key that is empty, repeated or one of the standard keys (or "nimbus_checksum").
Metadata export_metadata(const ExportInfo& info);

// Writes a density volume and its extra grids (temperature, flame...) to one file, atomically.
//
// `grids[0]` is the density grid; it is written as "density" and must be named "density" or
// nothing. The others keep their names, which must be non-empty and distinct, and must have
// exactly the density grid's transform (readers take "density" as the one mandatory grid and
// expect the others to match it). Every grid is written as a fog volume: class GRID_FOG_VOLUME, background 0,
// voxel size in metres from its transform, half float unless `options` say otherwise, the
// library's default compression (Blosc + active mask; OpenVDB's writer drops ZIP for fog volumes
// anyway, io::Archive::setGridCompression). The caller's grids are not modified. With
// info.up_axis == 'y' the grids are rotated so that world +Z becomes +Y (up_axis.hpp).
//
// Throws std::invalid_argument naming the grid for: no grids, a null grid, a wrong name, a
// transform that differs from the density grid's, a background other than 0, a non-finite
// value (active or not), or a value beyond the half-float range (65504) when saving as half;
// and for bad `info` (see export_metadata). Nothing is written then. Throws
// std::runtime_error naming `path` when writing fails; a file already at `path` is then left
// as it was.
void write_volume_vdb(const std::filesystem::path& path,
                      const std::vector<openvdb::FloatGrid::ConstPtr>& grids, const ExportInfo& info,
                      const ExportOptions& options = {});

}  // namespace nimbus::volume

// Bricks: a field too large for one process, cut into axis-aligned index boxes that separate
// processes (job-array tasks) generate, and joined again into one grid. Brick walls lie on
// multiples of 128 voxels, the span of OpenVDB's level-1 internal node (Tree_float_5_4_3: 16 x 8
// voxels), so no leaf or internal node of the tree is shared between bricks. Every voxel is a
// function of its world position alone (generate.hpp), so the joined bricks equal the field
// generated in one process, voxel for voxel.
#pragma once
#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::volume {

inline constexpr int kBrickAlign = 128;  // voxels; brick walls lie on multiples of this

// How a field's index box is cut: counts[a] bricks along axis a, brick i at (i % nx, i / nx %
// ny, i / (nx ny)).
struct BrickLayout {
  std::array<int, 3> counts{1, 1, 1};
  openvdb::CoordBBox field;  // every voxel of the field (inclusive), as density_index_box gives it
  int size() const { return counts[0] * counts[1] * counts[2]; }
  std::string text() const;  // "2x2x1"
};

// The layout for `counts_text`: "AxBxC" bricks along x, y, z, or one number N, cut so that the
// bricks are as near cubes as the 128-voxel blocks allow. Throws std::invalid_argument for
// malformed text, a count below 1 or above 4096 in all, or more bricks along an axis than the
// field has 128-voxel blocks there (a brick would be empty by construction).
BrickLayout make_brick_layout(const openvdb::CoordBBox& field, const std::string& counts_text);

// The index box (inclusive) of brick `index` (0-based): the 128-voxel blocks the brick owns,
// clipped to the field. Throws std::out_of_range for an index outside [0, size).
openvdb::CoordBBox brick_box(const BrickLayout& layout, int index);

// An identity of the field a brick belongs to: a 64-bit FNV-1a hash, as 16 hex digits, of the
// parameters (seed included), the voxel size, time, up axis and storage.
std::string field_identity(const CloudParams& params, const GenerateOptions& options, char up_axis,
                           bool half_float);

// File-level metadata keys a brick carries on top of export_metadata's.
struct BrickTag {
  int index = 0;
  BrickLayout layout;
  std::string field_id;
  bool half_float = true;  // the storage the joined file keeps
};
Metadata brick_metadata(const BrickTag& tag);

// Joins the brick files of one field into its grids (density first, then temperature when the
// bricks have it) and the metadata the one-process file would have had. Throws
// std::runtime_error naming the file for: a file that is not a nimbus brick, bricks of another
// field (naming what differs: preset, seed, time, layout, parameters), a brick given twice, a
// brick whose voxels leave its box, and missing bricks (listing their indices and boxes).
struct JoinedField {
  std::vector<openvdb::FloatGrid::Ptr> grids;  // z-up, density first
  ExportInfo info;                             // as the bricks' metadata, brick keys removed
  ExportOptions options;
  BrickLayout layout;
  int64_t active_voxels = 0;
};
JoinedField join_bricks(const std::vector<std::filesystem::path>& files);

}  // namespace nimbus::volume

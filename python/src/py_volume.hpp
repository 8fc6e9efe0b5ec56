// The module's Volume: a density (or any float grid read from a file) on a dense box of voxels (x
// fastest, so that NumPy sees it as an array indexed [x, y, z] without a copy), its transform, up
// axis, file metadata and extra grids.
#pragma once
#include <openvdb/openvdb.h>
#include <pybind11/pybind11.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nimbus/volume/vdb_io.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::python {

struct Volume {
  volume::DenseBox box;                            // density per voxel, x fastest (a read grid's values)
  std::string grid = "density";                    // the grid's name in the file it was read from
  openvdb::math::Transform::Ptr transform;         // index -> world, metres
  char up_axis = 'z';                              // of the world the transform places it in
  volume::Metadata metadata;                       // as a file carries it (vdb_io.hpp's keys)
  std::vector<openvdb::FloatGrid::ConstPtr> extra; // more grids (a gas's temperature), kept as made
};

// A generated or read grid (index box of its active voxels) as a Volume.
Volume volume_from_grid(const openvdb::FloatGrid& grid, char up_axis, volume::Metadata metadata);

// Writes `v` as `nimbus generate` writes its files (write_volume_vdb), atomically. ValueError
// (std::invalid_argument) for a NaN, Inf or negative value, naming the voxel: a file nimbus writes
// holds a density.
void write_volume(const Volume& v, const std::filesystem::path& path, bool half_float);

// std::invalid_argument naming the first voxel of `box` that is NaN or infinite, or negative unless
// `negatives_allowed` (`grid`: the volume's grid, named in the advice for a negative value).
void check_density(const volume::DenseBox& box, const std::string& grid = "density", bool negatives_allowed = false);

// The Volume behind a Python object; TypeError for another object or one never made.
Volume& volume_of(pybind11::handle self);

void bind_volume(pybind11::module_& m);

}  // namespace nimbus::python

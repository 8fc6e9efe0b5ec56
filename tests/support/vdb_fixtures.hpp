// Grids, temporary directories and shell commands for the VDB input/output tests.
#pragma once
#include <openvdb/openvdb.h>

#include <filesystem>
#include <string>

#include "support/run_nimbus.hpp"

namespace nimbus::test {

// A ball of `radius` voxels around index (0, 0, 0): density up to 5.7 (a real Houdini-written
// smoke file, smoke.vdb of the mjurczyk/openvdb examples, peaks at 5.71) falling to tiny values
// at the rim, with a ripple so neighbouring values differ. Active exactly where the distance is
// < radius.
openvdb::FloatGrid::Ptr make_ball(int radius, double voxel_size, const std::string& name = "density");

// A fresh directory for the running test, removed (with its content) when destroyed.
struct TempDir {
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path / name; }
  std::filesystem::path path;
};

std::string read_bytes(const std::filesystem::path& file);
void write_bytes(const std::filesystem::path& file, const std::string& bytes);

// Files in `dir` whose name contains ".tmp" (write_atomically's temporary files).
int count_temp_files(const std::filesystem::path& dir);


}  // namespace nimbus::test

// Private: opening a VDB file for reading with every failure turned into one
// std::runtime_error line that starts with the file name (used by vdb_read and vdb_info).
#pragma once
#include <openvdb/openvdb.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::volume::detail {

struct OpenedVdb {
  std::unique_ptr<openvdb::io::File> file;  // open, grids not yet read
  Metadata metadata;
  std::vector<GridInfo> grids;
  bool checksum_verified = false;
};

// Throws std::runtime_error naming the file unless it exists and is a regular file.
void check_regular_file(const std::filesystem::path& path);

// Checks the file exists and is a regular file, checks nimbus's seal when present, and opens
// it with OpenVDB (header, file metadata and grid descriptors; no grid data yet).
// `seal_verified`: the caller has just checked the seal and found it intact (skips the CRC).
OpenedVdb open_vdb(const std::filesystem::path& path, bool seal_verified = false);

// Reads one grid's data, rethrowing anything OpenVDB throws as std::runtime_error naming the
// file and the grid (std::bad_alloc passes through: it is a limit, not damage).
openvdb::GridBase::Ptr read_grid(OpenedVdb& vdb, const std::filesystem::path& path,
                                 const std::string& name);

// "a (float), b (int32)" for messages.
std::string list_grids(const std::vector<GridInfo>& grids);

}  // namespace nimbus::volume::detail

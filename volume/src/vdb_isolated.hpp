// Private: taking grids out of a VDB file without trusting it. nimbus's own sealed files (their
// CRC-32 checked first) are read in this process; any other file is opened, checked and read by
// OpenVDB in a forked child with a memory and time limit (isolated_call.hpp), which hands the
// grids back re-serialised by OpenVDB itself. A crash, an absurd allocation or an endless loop
// inside OpenVDB then costs the child, never the caller.
#pragma once
#include <openvdb/openvdb.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::volume::detail {

struct GridsRead {
  Metadata metadata;              // file-level
  std::vector<GridInfo> grids;    // every grid the file lists
  openvdb::GridPtrVec read;       // the grids chosen, with their data, in the order chosen
  bool checksum_verified = false;
  bool read_in_child = false;
};

// Picks the grids to read from the file's list; throws GridNotFound or std::runtime_error (whose
// messages name the file) when the choice cannot be made.
using GridChoice = std::function<std::vector<std::string>(const std::vector<GridInfo>&)>;

// Every error is one line naming the file: std::runtime_error (missing, not regular, damaged,
// crashed the reader, over the limits), GridNotFound from `choose`.
GridsRead read_grids(const std::filesystem::path& path, const GridChoice& choose, const VdbReadLimits& limits);

}  // namespace nimbus::volume::detail

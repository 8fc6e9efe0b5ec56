// Private: the isolated reader program's answer (vdb_reader_main.cpp -> vdb_isolated.cpp): the
// file's metadata, its grid list and the chosen grids, re-serialised by OpenVDB itself.
//
// One kind byte, then
//   'K': u8 checksum_verified, u32 metadata count, per entry (str key, u8 type, value),
//        u32 grid count, per grid (str name, str value type), then OpenVDB's stream of the
//        chosen grids (io::Stream, active-mask compression, half floats kept as stored);
//   'G': a GridNotFound message;   'R': any other error message.
// Strings are u32 length + bytes; numbers little-endian as in memory (same machine).
#pragma once
#include <openvdb/openvdb.h>

#include <string>
#include <vector>

#include "nimbus/volume/vdb_read.hpp"
#include "vdb_open.hpp"

namespace nimbus::volume::detail {

struct GridsRead {
  Metadata metadata;              // file-level
  std::vector<GridInfo> grids;    // every grid the file lists
  openvdb::GridPtrVec read;       // the grids chosen, with their data, in the order chosen
  bool checksum_verified = false;
  bool read_in_child = false;
};

// The reader's side.
void encode_answer(const OpenedVdb& vdb, const openvdb::GridPtrVec& read, std::string& out);
inline std::string grid_not_found_answer(const std::string& message) { return "G" + message; }
inline std::string error_answer(const std::string& message) { return "R" + message; }

// The caller's side: GridNotFound and std::runtime_error rethrown (one line, bounded), the
// grids read back otherwise; std::runtime_error when the answer is malformed.
GridsRead decode_answer(const std::string& answer);

}  // namespace nimbus::volume::detail

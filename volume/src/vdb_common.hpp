// Private plumbing shared by the OpenVDB writer, reader and summary: library start-up,
// nimbus::volume::Metadata <-> openvdb::MetaMap, and one-line error text.
#pragma once
#include <openvdb/openvdb.h>

#include <string>

#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::volume::detail {

// openvdb::initialize() once per process (it registers the grid and metadata types).
void init_openvdb();

// Strings stay strings, doubles doubles, int64 int64.
openvdb::MetaMap to_meta_map(const Metadata& metadata);

// float/double -> double, bool/int32/int64 -> int64, strings as they are, any other type
// (vectors, matrices) as OpenVDB prints it.
Metadata from_meta_map(const openvdb::MetaMap& meta);

// Newlines and tabs become spaces, so an error message stays one line; at most 400 characters
// of it are kept.
std::string one_line(std::string text);

}  // namespace nimbus::volume::detail

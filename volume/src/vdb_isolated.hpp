// Private: taking grids out of a VDB file without trusting it. nimbus's own sealed files (their
// CRC-32 checked first) are read in this process; any other file is opened, checked and read by
// OpenVDB in a program of its own, nimbus-vdb-reader (vdb_reader_main.cpp), started with a
// memory and time limit (base/isolated_call.hpp), which hands the grids back re-serialised by
// OpenVDB itself. A crash, an absurd allocation or an endless loop inside OpenVDB then costs that
// program, never the caller.
#pragma once
#include <filesystem>

#include "vdb_answer.hpp"
#include "vdb_grid_choice.hpp"

namespace nimbus::volume::detail {

// Every error is one line naming the file: std::runtime_error (missing, not regular, damaged,
// crashed the reader, over the limits, the reader program not found), GridNotFound.
GridsRead read_grids(const std::filesystem::path& path, const GridRequest& request, const VdbReadLimits& limits);

// The reader program: $NIMBUS_VDB_READER if set, else nimbus-vdb-reader beside the running
// executable, else the one in the build tree this library was built in. std::runtime_error
// saying where it looked when none is there.
std::filesystem::path vdb_reader_program();

}  // namespace nimbus::volume::detail

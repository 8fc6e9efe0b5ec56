// Private: a structural check of a VDB file's grid offsets against its size, before OpenVDB
// reads grid data. OpenVDB 10.0.1 reads a truncated file's missing Blosc chunk sizes as
// uninitialised memory and then asks for absurd allocations (std::bad_alloc, or an abort under
// AddressSanitizer); a file whose grids end past its last byte is refused here instead.
#pragma once
#include <filesystem>

namespace nimbus::volume::detail {

// Walks the header, the file metadata and every grid descriptor of a seekable VDB file (file
// format 222 to 224, written by OpenVDB 3 to 10+), checking that each grid's start and end
// offsets are ordered and within the file. Throws std::runtime_error naming the file when they
// are not, when the descriptors themselves run past the end, when the file is shorter than a
// magic number or does not start with one. Files of other format
// versions, and stream-written files without offsets, are left to OpenVDB.
void check_vdb_layout(const std::filesystem::path& file);

}  // namespace nimbus::volume::detail

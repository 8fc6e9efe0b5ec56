// Sealing the VDB files nimbus writes, and checking the seal before OpenVDB parses a file.
//
// The seal is the file metadata key
//   nimbus_checksum = "crc32=XXXXXXXX bytes=NNNNNNNNNNNNNNNN uuid=<the header UUID>":
// the CRC-32 of the whole file with that value read as the placeholder below, the file's size,
// and the header UUID, which ties the seal to this file: a tool that copies the metadata into
// a file of its own writes a new UUID, and the seal then counts as absent, not as damage. A reader checks it before it lets OpenVDB read any grid, because OpenVDB
// 10.0.1 returns garbage for flipped value bytes without noticing, and overflows a heap buffer
// on some corrupt Blosc chunk headers (io::bloscFromStream reads a chunk's stored size before
// checking it). Sealing also replaces the random UUID OpenVDB writes in the header with one
// derived from the content, so equal grids and metadata give byte-identical files.
#pragma once
#include <openvdb/openvdb.h>

#include <filesystem>
#include <optional>
#include <string>

namespace nimbus::volume::detail {

inline constexpr const char* kChecksumKey = "nimbus_checksum";

// The value written before sealing; sealing overwrites it in place with the same length.
std::string checksum_placeholder();

// The UUID a seal value names, if the value is well formed.
std::optional<std::string> seal_uuid(const std::string& value);

// Seals a file just written with the placeholder under kChecksumKey. `uuid` is the header UUID
// OpenVDB wrote (io::Archive::getUniqueTag()). Throws std::runtime_error naming `display`.
void seal_vdb_file(const std::filesystem::path& file, const std::string& uuid,
                   const std::filesystem::path& display);

// Writes `grids` and the file metadata `meta` to `path` atomically (write_atomically), sealed.
// OpenVDB's errors become std::runtime_error naming `path`.
void write_sealed_vdb(const std::filesystem::path& path, const openvdb::GridCPtrVec& grids,
                      openvdb::MetaMap meta);

enum class Seal { Verified, Absent };

// Verified: the CRC and size match. Absent: the file carries no seal of its own (written by
// another tool, or by nimbus before seals existed). Throws std::runtime_error naming the file when the seal is
// present but the file is truncated, extended or corrupt.
Seal check_vdb_seal(const std::filesystem::path& file);

}  // namespace nimbus::volume::detail

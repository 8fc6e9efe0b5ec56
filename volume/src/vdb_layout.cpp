// Grid-offset walk of VDB files (see vdb_layout.hpp). The layout follows OpenVDB's
// io::Archive::readHeader, MetaMap::readMeta, io::File::readGridDescriptors and
// io::GridDescriptor::read for file format 222 to 224.
#include "vdb_layout.hpp"

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

namespace nimbus::volume::detail {
namespace {

struct Reader {
  std::ifstream in;
  uint64_t size = 0;
  std::string name;

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(name + ": truncated or corrupt VDB file (" + what + ")");
  }
  uint64_t pos() { return uint64_t(in.tellg()); }
  void need(uint64_t bytes, const char* what) {
    if (bytes > size - pos()) fail(std::string(what) + " runs past the end of the file");
  }
  template <class T>
  T read(const char* what) {
    need(sizeof(T), what);
    T v{};
    in.read(reinterpret_cast<char*>(&v), sizeof(T));
    if (!in) fail(std::string("cannot read ") + what);
    return v;
  }
  void skip(uint64_t bytes, const char* what) {
    need(bytes, what);
    in.seekg(std::streamoff(bytes), std::ios::cur);
  }
  std::string read_string(const char* what) {
    const uint32_t len = read<uint32_t>(what);
    need(len, what);
    std::string s(len, '\0');
    in.read(s.data(), len);
    return s;
  }
};

}  // namespace

void check_vdb_layout(const std::filesystem::path& file) {
  Reader r;
  r.name = file.string();
  r.size = std::filesystem::file_size(file);
  r.in.open(file, std::ios::binary);
  if (!r.in) return;  // OpenVDB reports it itself
  // OpenVDB 10.0.1 reads a 4-7 byte prefix of a VDB file as a valid file holding no grids.
  if (r.size < 8)
    throw std::runtime_error(r.name + ": not a readable OpenVDB file (" + std::to_string(r.size) +
                             " bytes, too short to hold even its magic number)");
  if (r.read<int64_t>("magic number") != 0x56444220)  // OPENVDB_MAGIC
    throw std::runtime_error(r.name + ": not a readable OpenVDB file (it does not start with OpenVDB's magic number)");
  const uint32_t version = r.read<uint32_t>("file version");
  if (version < 222 || version > 224) return;
  r.skip(8, "library version");
  const char has_offsets = r.read<char>("header");
  r.skip(36, "UUID");
  if (!has_offsets) return;
  const uint32_t entries = r.read<uint32_t>("file metadata");
  for (uint32_t i = 0; i < entries; ++i) {
    r.read_string("file metadata name");
    r.read_string("file metadata type");
    r.skip(r.read<uint32_t>("file metadata size"), "file metadata value");
  }
  const int32_t grids = r.read<int32_t>("grid count");
  if (grids < 0) r.fail("negative grid count");
  for (int32_t g = 0; g < grids; ++g) {
    const std::string grid = r.read_string("grid name");
    r.read_string("grid type");
    r.read_string("grid instance parent");
    const int64_t grid_pos = r.read<int64_t>("grid offsets");
    const int64_t block_pos = r.read<int64_t>("grid offsets");
    const int64_t end_pos = r.read<int64_t>("grid offsets");
    const std::string which = "grid '" + grid + "'";
    if (!(int64_t(r.pos()) <= grid_pos && grid_pos <= block_pos && block_pos <= end_pos))
      r.fail(which + " has inconsistent offsets");
    if (uint64_t(end_pos) > r.size)
      r.fail(which + " ends at byte " + std::to_string(end_pos) + ", the file has " + std::to_string(r.size));
    r.in.seekg(std::streamoff(end_pos));
  }
}

}  // namespace nimbus::volume::detail

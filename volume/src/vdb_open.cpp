// Opening VDB files defensively: existence, nimbus's seal (or, without one, the grid offsets
// against the file size), then OpenVDB, whose exceptions
// (openvdb::IoError, RuntimeError, KeyError...) all become one line naming the file. An absurd
// size's std::bad_alloc passes through: in the reading child (vdb_isolated.hpp) it is the
// memory limit at work.
#include "vdb_open.hpp"

#include <stdexcept>

#include "vdb_common.hpp"
#include "vdb_layout.hpp"
#include "vdb_seal.hpp"

namespace nimbus::volume::detail {

void check_regular_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const std::string name = path.string();
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw std::runtime_error(name + ": no such file");
  if (fs::is_directory(st)) throw std::runtime_error(name + ": is a directory, not a VDB file");
  if (!fs::is_regular_file(st)) throw std::runtime_error(name + ": not a regular file (a device, FIFO or socket)");
}

OpenedVdb open_vdb(const std::filesystem::path& path, bool seal_verified) {
  const std::string name = path.string();
  check_regular_file(path);
  init_openvdb();
  OpenedVdb vdb;
  vdb.checksum_verified = seal_verified || check_vdb_seal(path) == Seal::Verified;
  if (!vdb.checksum_verified) check_vdb_layout(path);
  try {
    vdb.file = std::make_unique<openvdb::io::File>(name);
    vdb.file->open(/*delayLoad=*/false);  // read grids from the stream, no memory mapping
    vdb.metadata = from_meta_map(*vdb.file->getMetadata());
    const openvdb::GridPtrVecPtr grids = vdb.file->readAllGridMetadata();
    for (const auto& g : *grids) vdb.grids.push_back({g->getName(), g->valueType()});
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(name + ": not a readable OpenVDB file (" + one_line(e.what()) + ")");
  } catch (...) {
    throw std::runtime_error(name + ": not a readable OpenVDB file");
  }
  // A seal naming this file's UUID that the byte search did not find: its key or length bytes
  // are damaged.
  if (!vdb.checksum_verified)
    for (const auto& [key, value] : vdb.metadata)
      if (const auto* s = std::get_if<std::string>(&value); key == kChecksumKey && s)
        if (seal_uuid(*s) == vdb.file->getUniqueTag())
          throw std::runtime_error(name + ": corrupt VDB file (its checksum field is damaged)");
  return vdb;
}

openvdb::GridBase::Ptr read_grid(OpenedVdb& vdb, const std::filesystem::path& path, const std::string& name) {
  try {
    openvdb::GridBase::Ptr grid = vdb.file->readGrid(name);
    if (!grid) throw std::runtime_error("no data");
    return grid;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(path.string() + ": cannot read grid '" + name + "', the file is truncated or corrupt (" +
                             one_line(e.what()) + ")");
  } catch (...) {
    throw std::runtime_error(path.string() + ": cannot read grid '" + name + "', the file is truncated or corrupt");
  }
}

std::string list_grids(const std::vector<GridInfo>& grids) {
  if (grids.empty()) return "none";
  std::string out;
  for (const GridInfo& g : grids) out += (out.empty() ? "" : ", ") + g.name + " (" + g.value_type + ")";
  return out;
}

}  // namespace nimbus::volume::detail

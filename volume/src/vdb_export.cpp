// Sparse density volumes as fog-volume VDB files, with nimbus's file metadata
// (as Blender, Houdini and OpenVDB's tools expect them, docs/volume.md: grid "density", GRID_FOG_VOLUME, background 0,
// half float, Blosc, voxel size in metres, creator/preset/seed/time/frame/up axis/units).
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "nimbus/base/validate.hpp"
#include "nimbus/volume/up_axis.hpp"
#include "nimbus/volume/vdb_io.hpp"
#include "vdb_common.hpp"
#include "vdb_seal.hpp"

namespace nimbus::volume {
namespace {

std::string where(const openvdb::Coord& c) {
  std::ostringstream s;
  s << "(" << c[0] << ", " << c[1] << ", " << c[2] << ")";
  return s.str();
}

// A value that can reach the file as it is: finite, and finite again after rounding to half
// float when saved as half (|v| >= 65520 rounds to Inf; the largest half is 65504).
bool storable(float v, bool half_float) {
  return std::isfinite(v) && (!half_float || std::fabs(v) < 65504.0f || std::isfinite(float(openvdb::math::half(v))));
}

[[noreturn]] void refuse_value(const std::string& name, float v, const openvdb::Coord& at) {
  if (!std::isfinite(v)) throw std::invalid_argument("grid " + name + ": non-finite value at voxel " + where(at));
  throw std::invalid_argument("grid " + name + ": value " + number_text(v) + " at voxel " + where(at) +
                              " is beyond the half-float range (65504); write it as full float");
}

// No NaN or Inf may reach a file, active or not: leaf buffers are scanned whole (inactive
// voxels are stored too), then the tiles above them.
void check_values(const openvdb::FloatGrid& grid, const std::string& name, bool half_float) {
  for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
    const float* v = leaf->buffer().data();
    bool ok = true;
    for (openvdb::Index i = 0; i < leaf->SIZE; ++i) ok &= storable(v[i], half_float);
    if (!ok)
      for (openvdb::Index i = 0; i < leaf->SIZE; ++i)
        if (!storable(v[i], half_float)) refuse_value(name, v[i], leaf->offsetToGlobalCoord(i));
  }
  auto it = grid.tree().cbeginValueAll();
  it.setMaxDepth(it.getLeafDepth() - 1);  // tiles only
  for (; it; ++it)
    if (!storable(*it, half_float)) refuse_value(name, *it, it.getCoord());
}

}  // namespace

Metadata export_metadata(const ExportInfo& info) {
  if (info.up_axis != 'y' && info.up_axis != 'z')
    throw std::invalid_argument(std::string("up axis '") + info.up_axis + "' must be 'y' or 'z'");
  if (!std::isfinite(info.time)) throw std::invalid_argument("export time must be finite");
  if (info.fps && !(std::isfinite(*info.fps) && *info.fps > 0.0))
    throw std::invalid_argument("fps must be finite and > 0");
  if (info.units.empty()) throw std::invalid_argument("units must not be empty");
  const std::string version = info.nimbus_version.empty() ? library_version() : info.nimbus_version;
  Metadata meta = {
      {"creator", info.creator.empty() ? "nimbus " + version : info.creator},
      {"frame", info.frame},
      {"nimbus_version", version},
      {"preset", info.preset},
      {"seed", info.seed},
      {"time", info.time},
      {"units", info.units},
      {"up_axis", std::string(1, info.up_axis)},
  };
  if (info.fps) meta.emplace_back("fps", *info.fps);
  std::set<std::string> keys{detail::kChecksumKey};
  for (const auto& [key, value] : meta) keys.insert(key);
  for (const auto& [key, value] : info.extra) {
    if (key.empty()) throw std::invalid_argument("metadata: an extra key is empty");
    if (!keys.insert(key).second)
      throw std::invalid_argument("metadata: extra key '" + key + "' repeats a key nimbus writes or another extra key");
    meta.emplace_back(key, value);
  }
  std::sort(meta.begin(), meta.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return meta;
}

void write_volume_vdb(const std::filesystem::path& path,
                      const std::vector<openvdb::FloatGrid::ConstPtr>& grids, const ExportInfo& info,
                      const ExportOptions& options) {
  detail::init_openvdb();
  const Metadata file_meta = export_metadata(info);
  if (grids.empty()) throw std::invalid_argument("no grids to write (the density grid comes first)");
  std::set<std::string> names;
  for (size_t i = 0; i < grids.size(); ++i) {
    if (!grids[i]) throw std::invalid_argument("grid " + std::to_string(i) + " is null");
    const std::string given = grids[i]->getName();
    const std::string name = i == 0 ? "density" : given;
    if (i == 0 && !given.empty() && given != "density")
      throw std::invalid_argument("grid " + given + ": the first grid is the density grid and must be named density");
    if (name.empty()) throw std::invalid_argument("grid " + std::to_string(i) + ": an extra grid needs a name");
    if (!names.insert(name).second) throw std::invalid_argument("grid " + name + ": two grids have this name");
    if (i > 0 && !(grids[i]->transform() == grids[0]->transform()))
      throw std::invalid_argument("grid " + name + ": its transform differs from the density grid's");
    if (grids[i]->background() != 0.0f)
      throw std::invalid_argument("grid " + name + ": background must be 0 for a fog volume");
    check_values(*grids[i], name, options.half_float);
  }

  std::string creator;
  for (const auto& [key, value] : file_meta)
    if (key == "creator") creator = std::get<std::string>(value);
  openvdb::GridCPtrVec out;
  for (size_t i = 0; i < grids.size(); ++i) {
    openvdb::FloatGrid::Ptr g;
    if (info.up_axis == 'y') {
      g = rotate_z_up_to_y_up(*grids[i]);
    } else {
      // Shares the caller's tree (writing only reads it) under fresh metadata and transform.
      g = openvdb::gridPtrCast<openvdb::FloatGrid>(grids[i]->copyGridWithNewTree());
      g->setTree(std::const_pointer_cast<openvdb::FloatTree>(grids[i]->constTreePtr()));
    }
    g->setName(i == 0 ? "density" : grids[i]->getName());
    g->setGridClass(openvdb::GRID_FOG_VOLUME);
    g->setCreator(creator);
    g->setSaveFloatAsHalf(options.half_float);
    out.push_back(g);
  }
  detail::write_sealed_vdb(path, out, detail::to_meta_map(file_meta));
}

}  // namespace nimbus::volume

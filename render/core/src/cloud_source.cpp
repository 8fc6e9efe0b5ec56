// Clouds from VDB files and presets (cloud_source.hpp).
#include "nimbus/render/core/cloud_source.hpp"

#include "nimbus/render/core/cloud_tiles.hpp"
#include "nimbus/render/core/world_axes.hpp"

#include <openvdb/tools/ChangeBackground.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <variant>

#include "nimbus/base/memory.hpp"
#include "nimbus/volume/cloud_model.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/up_axis.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::render {

UpAxis parse_up_axis(const std::string& text) {
  if (text == "auto") return UpAxis::Auto;
  if (text == "y") return UpAxis::Y;
  if (text == "z") return UpAxis::Z;
  throw std::invalid_argument("up axis '" + text + "' must be auto, y or z");
}

namespace {

// A density cannot be negative: negative values and a negative background become 0, told in one
// line naming `name` (`negatives` of them, the least `least`).
void zero_negatives(openvdb::FloatGrid& grid, uint64_t negatives, float least, const std::string& name,
                    const CloudFileOptions& options) {
  const bool negative_background = grid.background() < 0.0f;
  if (negatives == 0 && !negative_background) return;
  for (auto it = grid.beginValueAll(); it; ++it)
    if (*it < 0.0f) it.setValue(0.0f);
  if (negative_background) openvdb::tools::changeBackground(grid.tree(), 0.0f);
  if (options.warn) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(std::min(least, grid.background())));
    options.warn(name + ": grid '" + grid.getName() + "' holds " + std::to_string(negatives) + " negative value(s)" +
                 (negative_background ? " and a negative background" : "") + " (least " + text +
                 "); a density cannot be negative, so they are read as 0");
  }
}

// What the metadata says of the grid: whether it is z-up (where `up` is Auto), its period, its fps.
bool read_cloud_metadata(const volume::Metadata& metadata, UpAxis up, const std::string& name, double* fps,
                         glm::dvec3* period_m) {
  bool z_up = up == UpAxis::Z;
  for (const auto& [key, value] : metadata) {
    const std::string* text = std::get_if<std::string>(&value);
    if (up == UpAxis::Auto && key == "up_axis" && text && *text == "z") z_up = true;
    if (period_m && key == volume::kPeriodMetadataKey) {
      double px = 0.0, py = 0.0;
      char rest = 0;
      if (!text || std::sscanf(text->c_str(), "%lf %lf %c", &px, &py, &rest) != 2 || !std::isfinite(px) ||
          !std::isfinite(py) || px < 0.0 || py < 0.0 || px > 1e7 || py > 1e7)
        throw std::runtime_error(name + ": metadata '" + volume::kPeriodMetadataKey + "' must be two periods in [0, 1e7] metres, 'PX PY'");
      *period_m = glm::dvec3(px, 0.0, py);  // the world's x and y are the renderer's x and z
    }
    if (fps && key == "fps") {
      if (const double* d = std::get_if<double>(&value)) *fps = *d;
      if (const int64_t* n = std::get_if<int64_t>(&value)) *fps = static_cast<double>(*n);
    }
  }
  return z_up;
}

}  // namespace

openvdb::FloatGrid::Ptr load_cloud_grid(const std::string& path, const std::string& grid, UpAxis up, double* fps,
                                        const CloudFileOptions& options, glm::dvec3* period_m) {
  volume::VdbReadOptions ro;
  if (!grid.empty()) ro.grid = grid;
  ro.level_set_to_fog = options.level_set_to_fog;
  volume::VolumeFile f = volume::read_volume_vdb(path, ro);
  zero_negatives(*f.grid, f.negative_values, f.min_value, path, options);
  const bool z_up = read_cloud_metadata(f.metadata, up, path, fps, period_m);
  return z_up ? volume::rotate_z_up_to_y_up(*f.grid) : f.grid;
}

openvdb::FloatGrid::Ptr cloud_grid_in_memory(const openvdb::FloatGrid& grid, const volume::Metadata& metadata,
                                             UpAxis up, const std::string& name, const CloudFileOptions& options,
                                             glm::dvec3* period_m) {
  openvdb::FloatGrid::Ptr g = grid.deepCopy();
  uint64_t negatives = 0;
  float least = 0.0f;
  for (auto it = g->cbeginValueOn(); it; ++it) {
    if (!std::isfinite(*it)) throw std::invalid_argument(name + ": holds a NaN or infinite value; a density is finite");
    if (*it < 0.0f) ++negatives;
    least = std::min(least, *it);
  }
  zero_negatives(*g, negatives, least, name, options);
  const bool z_up = read_cloud_metadata(metadata, up, name, nullptr, period_m);
  return z_up ? volume::rotate_z_up_to_y_up(*g) : g;
}

CloudVolume load_cloud_file(const std::string& path, const std::string& grid, UpAxis up, const CloudOptics& optics,
                            const CloudFileOptions& options) {
  glm::dvec3 period(0.0);
  const openvdb::FloatGrid::Ptr g = load_cloud_grid(path, grid, up, nullptr, options, &period);
  return cloud_from_grid(*g, period, optics, path);
}

CloudVolume cloud_from_grid(const openvdb::FloatGrid& grid, glm::dvec3 period_m, const CloudOptics& optics,
                            const std::string& name) {
  // The grid's own errors (a box too large to copy densely, a frustum transform...) name it.
  CloudVolume c;
  try {
    c = make_cloud_volume(grid, optics, name);
  } catch (const OutOfMemoryRequest& e) {
    throw OutOfMemoryRequest(name + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    throw std::invalid_argument(what.find(name) == std::string::npos ? name + ": " + what : what);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(name + ": " + e.what());
  }
  c.period_m = period_m;
  // A period shorter than the cloud is the file's fault (its metadata), not the command line's.
  if (const std::string fault = period_fault(c); !fault.empty())
    throw std::runtime_error(name + ": metadata '" + volume::kPeriodMetadataKey + "': the period " + fault);
  // World extents a camera can frame: a voxel of 1e300 m once reached the camera as Inf.
  constexpr double kMaxWorld = 1e8;  // metres
  for (int a = 0; a < 3; ++a)
    if (!(std::abs(c.world_min[a]) < kMaxWorld && std::abs(c.world_max[a]) < kMaxWorld))
      throw std::runtime_error(name + ": its grid reaches beyond 1e8 m from the origin (voxel size " +
                               std::to_string(grid.voxelSize()[0]) + " m); not a cloud nimbus can frame");
  return c;
}

PresetCloud load_preset_cloud(const std::string& name) {
  const nlohmann::json doc = volume::load_preset(name);
  PresetCloud p;
  p.name = name;
  p.params = volume::cloud_from_json(doc.at("cloud"), name);
  p.voxel_size_m = volume::preset_voxel_size(doc, name);
  return p;
}

CloudVolume generate_preset_cloud(const PresetCloud& preset, std::optional<double> voxel_size_m, double time_s,
                                  const CloudOptics& optics, const std::function<void(double)>& progress) {
  volume::GenerateOptions opt;
  opt.voxel_size = voxel_size_m.value_or(preset.voxel_size_m);
  opt.time = time_s;
  opt.progress = progress;
  opt.y_up = true;  // the renderer's axes, made directly
  const auto grid = volume::generate_density(preset.params, opt);
  CloudVolume c = make_cloud_volume(*grid, optics, preset.name);
  c.period_m = render_period(preset.params);
  return c;
}

glm::dvec3 render_period(const volume::CloudParams& params) {
  const std::optional<volume::PeriodicTile> tile = volume::periodic_tile(params);
  if (!tile) return glm::dvec3(0.0);
  return glm::abs(world_to_render(glm::dvec3(tile->size_m, 0.0)));
}

}  // namespace nimbus::render

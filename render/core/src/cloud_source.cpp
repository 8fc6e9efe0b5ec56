// Clouds from VDB files and presets (cloud_source.hpp).
#include "nimbus/render/core/cloud_source.hpp"

#include <stdexcept>
#include <variant>

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

openvdb::FloatGrid::Ptr load_cloud_grid(const std::string& path, const std::string& grid, UpAxis up, double* fps) {
  volume::VolumeFile f = volume::read_volume_vdb(path, grid.empty() ? std::nullopt : std::optional(grid));
  bool z_up = up == UpAxis::Z;
  for (const auto& [key, value] : f.metadata) {
    const std::string* text = std::get_if<std::string>(&value);
    if (up == UpAxis::Auto && key == "up_axis" && text && *text == "z") z_up = true;
    if (fps && key == "fps") {
      if (const double* d = std::get_if<double>(&value)) *fps = *d;
      if (const int64_t* n = std::get_if<int64_t>(&value)) *fps = static_cast<double>(*n);
    }
  }
  return z_up ? volume::rotate_z_up_to_y_up(*f.grid) : f.grid;
}

CloudVolume load_cloud_file(const std::string& path, const std::string& grid, UpAxis up, const CloudOptics& optics) {
  return make_cloud_volume(*load_cloud_grid(path, grid, up), optics, path);
}

PresetCloud load_preset_cloud(const std::string& name) {
  const nlohmann::json doc = volume::load_preset(name);
  PresetCloud p;
  p.name = name;
  p.params = volume::cloud_from_json(doc.at("cloud"), name);
  p.voxel_size_m = doc.value("voxel_size", 25.0);
  return p;
}

CloudVolume generate_preset_cloud(const PresetCloud& preset, std::optional<double> voxel_size_m, double time_s,
                                  const CloudOptics& optics, const std::function<void(double)>& progress) {
  volume::GenerateOptions opt;
  opt.voxel_size = voxel_size_m.value_or(preset.voxel_size_m);
  opt.time = time_s;
  opt.progress = progress;
  const auto grid = volume::generate_density(preset.params, opt);
  return make_cloud_volume(*volume::rotate_z_up_to_y_up(*grid), optics, preset.name);
}

}  // namespace nimbus::render

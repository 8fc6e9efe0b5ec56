// Where clouds come from: a fog grid in a VDB file (turned y-up from its up_axis metadata) or a
// preset generated at a time. What `nimbus render` and the viewer load, frame after frame.
#pragma once
#include <functional>
#include <optional>
#include <string>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/volume/cloud_model.hpp"

namespace nimbus::render {

// Which axis of a file points up. Auto: its "up_axis" metadata ("z" or "y"), else y. nimbus
// renders y-up, so z-up grids are turned (x, y, z) -> (x, z, -y).
enum class UpAxis { Auto, Y, Z };
// "auto", "y", "z"; std::invalid_argument naming the text otherwise.
UpAxis parse_up_axis(const std::string& text);

// The float grid `grid` (empty: "density", else the first float grid) of the VDB file at `path`,
// y-up, as a cloud named by the path. Missing or damaged files throw std::runtime_error, an
// unknown grid volume::GridNotFound (both naming the file), and a box too large to hold
// OutOfMemoryRequest.
CloudVolume load_cloud_file(const std::string& path, const std::string& grid, UpAxis up, const CloudOptics& optics);
// The same grid, y-up, before it becomes a cloud (the viewer keeps keyframes as grids). `fps`:
// the file's "fps" metadata when it has one.
openvdb::FloatGrid::Ptr load_cloud_grid(const std::string& path, const std::string& grid, UpAxis up,
                                        double* fps = nullptr);

// A preset's cloud parameters and its own voxel size (metres); std::invalid_argument naming an
// unknown preset or a bad parameter.
struct PresetCloud {
  std::string name;
  volume::CloudParams params;
  double voxel_size_m = 25.0;
};
PresetCloud load_preset_cloud(const std::string& name);

// The preset generated at `time_s` (its density field is a pure function of parameters, seed and
// time), turned y-up. voxel_size_m: nullopt = the preset's own. progress may be empty.
CloudVolume generate_preset_cloud(const PresetCloud& preset, std::optional<double> voxel_size_m, double time_s,
                                  const CloudOptics& optics, const std::function<void(double)>& progress = {});

}  // namespace nimbus::render

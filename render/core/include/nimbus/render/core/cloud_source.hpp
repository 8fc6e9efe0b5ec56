// Where clouds come from: a fog grid in a VDB file (turned y-up from its up_axis metadata) or a
// preset generated at a time. What `nimbus render` and the viewer load, frame after frame.
#pragma once
#include <functional>
#include <optional>
#include <string>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/volume/cloud_model.hpp"
#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::render {

// Which axis of a file points up. Auto: its "up_axis" metadata ("z" or "y"), else y. nimbus
// renders y-up, so z-up grids are turned (x, y, z) -> (x, z, -y).
enum class UpAxis { Auto, Y, Z };
// "auto", "y", "z"; std::invalid_argument naming the text otherwise.
UpAxis parse_up_axis(const std::string& text);

// How a file's grid becomes a density.
struct CloudFileOptions {
  bool level_set_to_fog = false;  // a level set becomes a fog volume (else it is refused)
  // Told, in one line naming the file, when negative values (which a density cannot hold) were
  // read as 0. May be empty.
  std::function<void(const std::string&)> warn;
};

// The float grid `grid` (empty: "density", else the first float grid) of the VDB file at `path`,
// y-up, as a cloud named by the path. Foreign files are read in an isolated child process
// (volume/vdb_read.hpp). Missing, damaged or hostile files and level sets throw
// std::runtime_error, an unknown grid volume::GridNotFound (both naming the file), and a box too
// large to hold OutOfMemoryRequest. Negative values (and a negative background) become 0.
// A file whose "period_m" metadata (volume::kPeriodMetadataKey) holds two numbers "PX PY" (the world's x and y periods of a
// periodic field, metres, as `nimbus generate` writes them) gets them as its period
// (CloudVolume::period_m); anything else in that key is refused as a damaged file.
CloudVolume load_cloud_file(const std::string& path, const std::string& grid, UpAxis up, const CloudOptics& optics,
                            const CloudFileOptions& options = {});
// The same grid, y-up, before it becomes a cloud (the viewer keeps keyframes as grids). `fps`:
// the file's "fps" metadata when it has one.
openvdb::FloatGrid::Ptr load_cloud_grid(const std::string& path, const std::string& grid, UpAxis up,
                                        double* fps = nullptr, const CloudFileOptions& options = {},
                                        glm::dvec3* period_m = nullptr);

// A grid held in memory (the Python module's Volume), made ready as load_cloud_grid makes a file's:
// a copy with negative values read as 0 (told through options.warn), turned y-up where `up` (Auto:
// the "up_axis" metadata) says z, its period from the metadata. `name` names it in errors;
// std::invalid_argument for a NaN or infinite value.
openvdb::FloatGrid::Ptr cloud_grid_in_memory(const openvdb::FloatGrid& grid, const volume::Metadata& metadata,
                                             UpAxis up, const std::string& name, const CloudFileOptions& options = {},
                                             glm::dvec3* period_m = nullptr);

// A y-up grid (load_cloud_grid, cloud_grid_in_memory) as the cloud named `name`, with its period;
// the errors of load_cloud_file, each naming `name`.
CloudVolume cloud_from_grid(const openvdb::FloatGrid& grid, glm::dvec3 period_m, const CloudOptics& optics,
                            const std::string& name);

// A preset's cloud parameters and its own voxel size (metres); std::invalid_argument naming an
// unknown preset or a bad parameter.
struct PresetCloud {
  std::string name;
  volume::CloudParams params;
  double voxel_size_m = 25.0;
};
PresetCloud load_preset_cloud(const std::string& name);

// The period of cloud parameters' periodic tile (volume::periodic_tile) in the renderer's frame, as
// CloudVolume::period_m takes it: the world's x and y periods along render x and z; 0 when the
// parameters do not repeat.
glm::dvec3 render_period(const volume::CloudParams& params);

// The preset generated at `time_s` (its density field is a pure function of parameters, seed and
// time), turned y-up, with its period (render_period). voxel_size_m: nullopt = the preset's own.
// progress may be empty.
CloudVolume generate_preset_cloud(const PresetCloud& preset, std::optional<double> voxel_size_m, double time_s,
                                  const CloudOptics& optics, const std::function<void(double)>& progress = {});

}  // namespace nimbus::render

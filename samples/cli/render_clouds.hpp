// `nimbus render FILE.vdb | --preset NAME`: clouds by half-angle slicing (or the CPU reference),
// over the sky scene, another scene or nothing, one frame or a sequence.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cli.hpp"
#include "frame_range.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "nimbus/render/media/shaft_method.hpp"
#include "nimbus/render/sky/request_settings.hpp"
#include "render_args.hpp"
#include "sun_flags.hpp"

namespace nimbus::cli {

// The scene's light-shaft method under the clouds when --shafts is left out.
inline constexpr const char* kCloudShaftsDefault = "raymarch:48";

// The request `nimbus render` and Python start from: the table's still defaults, the shaft method
// above, the library's optics.
inline render::RenderRequest still_request() {
  render::RenderRequest r;
  render::set_setting_defaults(r, render::SettingDefaults::Still);
  r.shafts = render::parse_shaft_method(kCloudShaftsDefault);
  return r;
}

// A cloud held in memory (the Python module's Volume), rendered among the files as the file it
// would be written to: its grid made ready by render::cloud_grid_in_memory.
struct MemoryCloud {
  std::string name;                   // in errors: "volumes_or_paths[1] (a Volume)"
  openvdb::FloatGrid::ConstPtr grid;  // y-up, no negative value
  glm::dvec3 period_m{0.0};           // its periodic tile's world x and y periods, as render x and z
  std::size_t position = 0;           // its place among the clouds: before files[position]
};

struct CloudRenderArgs {
  std::vector<std::string> files;    // VDB files (a '%04d'-style pattern with --frames)
  std::vector<MemoryCloud> memory;   // clouds in memory, in order of position (not a flag)
  std::vector<std::string> presets;  // generated at --time or per frame
  std::string grid;                  // grid name in the files (default: density, else the first float grid)
  std::string up = "auto";           // up axis of the files: auto (their metadata, else y), y or z
  bool level_set_to_fog = false;     // a level set in a file becomes a fog volume (else refused)
  std::optional<double> voxel_size;  // metres, presets
  FrameArgs frame;                   // --time or --frames (presets at each frame's time)
  SunArgs sun;                       // --sun, --sun-elevation/--sun-azimuth or --time-of-day
  // The flags below are typed: their text is parsed as the command line is read (typed_option.hpp).
  std::vector<glm::dvec3> lamps;     // each lamp on the clouds, renderer frame, metres (joins a scene's point lights)
  glm::dvec3 lamp_intensity_w_sr{100.0};  // every --lamp, per channel
  std::optional<glm::dvec3> spot_axis;    // every --lamp is a spot shining that way (renderer frame, non-zero)
  glm::dvec2 spot_cone_deg{20.0, 30.0};   // inner, outer half-angles of the spot's cone, 0 < inner <= outer <= 180
  // What a request file would hold (render_request.hpp), at a still's defaults: the table's
  // numbers (render_settings.hpp; --fov and --exposure are the render command's own, in every
  // mode), the optics' albedo and phase, the scene's shaft method, jitter, the grain filter.
  render::RenderRequest request = still_request();
  // --request FILE: a render request's JSON (render_request.hpp; a view state's scene, camera,
  // optics and renderer), read before the flags, which override it. Its camera is used as it is
  // (not framed on the clouds), its exposure is the preview's, and its render_scale is the
  // viewer's alone.
  std::string request_file;
  std::set<render::Setting> settings_given;  // the table's settings given a value (not auto) by a flag
  bool surface_airlight = true;      // the scene's surfaces reflect the fog's airlight (--no-surface-airlight)
  std::optional<glm::dvec3> ambient;                // W m^-2 sr^-1; unset (auto): the sky's mean radiance, else 0
  std::optional<render::MultipleScatteringMethod> ms_method;  // unset: light-volume unless --multiple N > 0 asks for octaves
  int spp = 64;                      // pathtrace: samples per pixel
  int bounces = 1000;                // pathtrace: scattering events per path at most
  uint64_t seed = 1;                 // pathtrace
  std::set<std::string> given;       // the flags given on the command line ("--spot-cone"): a flag that
                                     // qualifies another one must not be given without it
};

void add_cloud_render_options(CLI::App* cmd, CloudRenderArgs& args);
// --scene, --method and --no-surface-airlight, as `nimbus render` spells them.
void add_scene_options(CLI::App* cmd, std::string& scene, std::string& method, bool& no_surface_airlight);

// Where each rendered frame goes instead of files (the Python module): called once per frame.
using FrameSink = std::function<void(render::Image& image, int frame)>;

// Runs when files or presets were given. `scene`, `method`, camera, outputs as `nimbus render`.
// With a sink, `output` and `preview` are empty: nothing is written, the sink takes each frame.
int run_render_clouds(const CloudRenderArgs& a, const std::string& scene_name, bool scene_given,
                      const std::string& method, bool method_given, const CameraArgs& camera_args,
                      const std::string& output, const std::string& preview, std::optional<double> exposure,
                      const FrameSink& sink = {});

}  // namespace nimbus::cli

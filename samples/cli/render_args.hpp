// Camera and image-size flags shared by `nimbus render` and `nimbus bench shafts`, spelled as
// OpenVDB's vdb_render spells them: --eye X,Y,Z --look-at X,Y,Z --up X,Y,Z --fov DEG --res WxH,
// in nimbus's Z-up world (x east, y north, z up).
#pragma once
#include <optional>
#include <string>

#include "cli.hpp"
#include <vector>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/gl/resources.hpp"

namespace nimbus::cli {

struct CameraArgs {
  std::string eye, look_at, up, res;
  std::optional<double> fov_deg;
};

void add_camera_options(CLI::App* cmd, CameraArgs& args);

// Each given camera flag on its own (its syntax and range), UsageError naming it: for a command
// that applies them only after its checks (a camera framed on clouds it has yet to load).
void check_camera_flags(const CameraArgs& args);

// The scene's default camera with the given flags applied; bad values -> UsageError naming the flag.
render::Camera apply_camera_args(const CameraArgs& args, render::Camera camera);

// The largest magnitude a number of a render flag may have (positions, directions, radiances,
// extinctions): beyond it the GPU's floats (and lengths in double) overflow into NaN pixels.
inline constexpr double kMaxFlagMagnitude = 1e12;

// "X,Y,Z" -> vector; UsageError naming `flag` when malformed, not finite, or beyond
// +-kMaxFlagMagnitude.
glm::dvec3 parse_vec3(const std::string& flag, const std::string& text);
// A point or direction of nimbus's Z-up world given on the command line (x east, y north, z up),
// in the renderer's frame (world_axes.hpp). Every position and direction flag goes through it.
glm::dvec3 parse_world_vec3(const std::string& flag, const std::string& text);

// --exposure: UsageError unless within the table's range (render_settings.hpp; 2^64 already
// overflows a half float).
void check_exposure(const std::optional<double>& stops);
// "WxH" -> width, height in [1, 16384]; UsageError naming `flag` otherwise.
std::pair<int, int> parse_resolution(const std::string& flag, const std::string& text);
// A comma-separated list of WxH (the benches' --sizes); UsageError naming `flag` for a bad one
// or an empty list.
std::vector<std::pair<int, int>> parse_resolutions(const std::string& flag, const std::string& list);


// Runs a GPU render; a GL_OUT_OF_MEMORY on the way becomes std::runtime_error naming `size_flag`
// and the size it asked for ("--res 16384x16384: ..."), since the frame's buffers are what grew.
template <typename F>
auto naming_gpu_memory(const std::string& size_flag, int width, int height, F&& render) -> decltype(render()) {
  try {
    return render();
  } catch (const render::GlError& e) {
    if (!e.out_of_memory) throw;
    throw std::runtime_error(size_flag + " " + std::to_string(width) + "x" + std::to_string(height) +
                             ": the GPU ran out of memory for the frame's buffers (" + e.what() + "); render smaller");
  }
}

// "a,b,,c" -> {"a", "b", "c"}: the comma-separated lists of the benchmarks' flags.
std::vector<std::string> split_list(const std::string& text);

// The exact CPU reference with its progress on stderr (shared by render and bench shafts).
render::Image render_reference_with_progress(const render::Scene& scene, const render::Camera& camera,
                                             bool surface_airlight = true);

}  // namespace nimbus::cli

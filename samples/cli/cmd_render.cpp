// `nimbus render`: a light-shaft scene rendered by one of the GPU methods (on a headless GL
// context) or by the exact CPU reference, written as a linear half-float EXR (and a PNG preview).
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <optional>
#include <regex>

#include "cli.hpp"
#include "nimbus/render/media/medium.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"
#include "outputs.hpp"
#include "progress.hpp"
#include "render_args.hpp"
#include "render_clouds.hpp"
#include "render_modes.hpp"
#include "render_view_state.hpp"
#include "setting_flags.hpp"

namespace nimbus::cli {
namespace {

struct RenderArgs {
  std::string scene = "lamps";
  std::string method = "shadowvolume:32";
  CameraArgs camera;
  std::string jitter = "blue";
  int shadow_res = 1024;
  std::optional<double> extinction, albedo;
  std::string phase;
  std::string preview;
  std::optional<double> exposure;
  std::string output;
  bool hide_bulbs = false;
  bool no_surface_airlight = false;
  CloudRenderArgs clouds;
  std::string view_state;
  bool scene_given = false, method_given = false;
};

int run_render(const RenderArgs& a, const CLI::App& cmd) {
  if (a.output.empty()) throw UsageError("-o: an output file (.exr) is required");
  // The image is always a linear EXR: a name that says otherwise (out.png) would get EXR bytes.
  const auto ends_with = [](const std::string& s, const std::string& tail) {
    if (s.size() < tail.size()) return false;
    for (std::size_t i = 0; i < tail.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(s[s.size() - tail.size() + i])) != tail[i]) return false;
    return true;
  };
  if (!ends_with(a.output, ".exr"))
    throw UsageError("-o '" + a.output + "': the image is written as linear OpenEXR, so its name must end in .exr (a PNG: --preview)");
  if (!a.preview.empty() && !ends_with(a.preview, ".png"))
    throw UsageError("--preview '" + a.preview + "': the preview is a PNG, so its name must end in .png");
  if (!a.view_state.empty()) {
    if (!a.clouds.files.empty() || !a.clouds.presets.empty() || a.scene_given || a.method_given)
      throw UsageError("--view-state: the state holds the clouds, scene and method; give none of FILE, --preset, --scene, --method");
    if (!a.camera.eye.empty() || !a.camera.look_at.empty() || !a.camera.up.empty() || a.camera.fov_deg)
      throw UsageError("--view-state: the camera comes from the state; only --res may be given");
    check_render_flags(cmd, kRenderViewState);
    const int samples = cmd.count("--spp") > 0 ? a.clouds.spp : 1;
    return run_render_view_state(a.view_state, a.camera, a.output, a.preview, a.exposure, samples, a.clouds.request.grain_filter.on);
  }
  if (!a.clouds.files.empty() || !a.clouds.presets.empty()) {
    check_render_flags(cmd, kRenderClouds);
    CloudRenderArgs clouds = a.clouds;
    for (const CLI::Option* o : cmd.get_options())
      if (o->count() > 0) clouds.given.insert(o->get_name());
    clouds.surface_airlight = !a.no_surface_airlight;  // the scene's surfaces under the clouds
    return run_render_clouds(clouds, a.scene, a.scene_given, a.method, a.method_given, a.camera, a.output, a.preview,
                             a.exposure);
  }
  check_render_flags(cmd, kRenderScene);
  render::Scene scene;
  try {
    scene = render::make_scene(a.scene);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--scene: ") + e.what());
  }
  if (a.hide_bulbs)
    for (render::Light& l : scene.lamps) l.bulb_radius_m = 0.0;
  if (a.extinction && !(std::abs(*a.extinction) <= kMaxFlagMagnitude))
    throw UsageError("--extinction: must be at most 1e12 per metre");
  if (a.extinction) scene.medium.extinction_per_m = *a.extinction;
  if (a.albedo) scene.medium.albedo = *a.albedo;
  if (!a.phase.empty()) {
    try {
      scene.medium.phase = render::parse_medium_phase(a.phase);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--phase: ") + e.what());
    }
  }
  try {
    render::validate(scene.medium);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--extinction/--albedo: ") + e.what());
  }
  const render::Camera camera = apply_camera_args(a.camera, scene.camera);
  render::ShaftMethod method;
  try {
    method = render::parse_shaft_method(a.method);
    method.jitter = render::parse_jitter(a.jitter);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--method/--jitter: ") + e.what());
  }
  if (a.shadow_res < 16 || a.shadow_res > 8192) throw UsageError("--shadow-res: must be in [16, 8192]");
  check_exposure(a.exposure);
  check_outputs({{"-o", a.output}, {"--preview", a.preview}});
  checks_done();

  const auto start = std::chrono::steady_clock::now();
  render::Image image;
  std::string device, gpu_times;
  if (method.kind == render::ShaftMethod::Kind::Reference) {
    image = render_reference_with_progress(scene, camera, !a.no_surface_airlight);
    device = "CPU (double precision)";
  } else {
    std::unique_ptr<render::GlContext> gl;
    try {
      gl = render::GlContext::create_headless();
    } catch (const render::GlUnavailable& e) {
      throw std::runtime_error(std::string("method ") + a.method + " needs OpenGL: " + e.what());
    }
    render::ShaftSettings settings;
    settings.point_shadow_res = a.shadow_res;
    settings.sun_shadow_res = 2 * a.shadow_res;
    settings.surface_airlight = !a.no_surface_airlight;
    render::ShaftRenderer renderer(scene, settings);
    render::ShaftFrameStats stats;
    try {
      image = naming_gpu_memory("--res", camera.width, camera.height, [&] { return renderer.render(camera, method, &stats); });
    } catch (const std::runtime_error& e) {  // a non-finite pixel: name what was rendered, not only the stage
      throw std::runtime_error("rendering scene " + scene.name + " (--method " + a.method + ", flags as given): " + e.what());
    }
    device = gl->renderer();
    char line[256];
    std::snprintf(line, sizeof line, "GPU ms: shadow maps %.1f, surfaces %.1f, shadow volume %.1f (%zu skirts), shafts %.1f (%s)\n",
                  stats.shadow_maps_ms, stats.surfaces_ms, stats.shadow_volume_ms, stats.skirt_quads, stats.shafts_ms,
                  stats.timing.c_str());
    gpu_times = line;  // printed once the files are written: a failed run prints its error alone
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  image.metadata["device"] = device;
  render::PreviewOptions po;
  if (!a.preview.empty()) po.exposure_stops = a.exposure ? *a.exposure : render::auto_exposure_stops(image);
  write_image_files(a.output, a.preview, image, po);
  warn_half_float_clipping(image, a.output, "the scene's lights (--scene " + scene.name + ") or --extinction/--albedo");
  std::fputs(gpu_times.c_str(), stderr);
  std::fprintf(stderr, "%s: %s %dx%d, %s, %.2f s on %s\n", a.output.c_str(), scene.name.c_str(), camera.width,
               camera.height, render::to_string(method).c_str(), seconds, device.c_str());
  return 0;
}

}  // namespace

void add_scene_options(CLI::App* cmd, std::string& scene, std::string& method, bool& no_surface_airlight) {
  cmd->add_option("--scene", scene, "Scene: " + [] {
    std::string names;
    for (const std::string& n : render::scene_names()) names += (names.empty() ? "" : ", ") + n;
    return names + "; with clouds also none (default with clouds: sky)";
  }())->capture_default_str();
  cmd->add_option("--method", method,
                  "Scene alone: raymarch:N | analytic | analytic:table:N | shadowvolume:N | reference. "
                  "With clouds: slices | reference | pathtrace (the CPU methods: --scene none only)")
      ->capture_default_str();
  cmd->add_flag("--no-surface-airlight", no_surface_airlight,
                "Surfaces do not reflect the fog's airlight (Sun et al. eq. 13's L_p,a; on by default)");
}

void add_render_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render clouds (FILE.vdb or --preset) over a scene, or a light-shaft scene alone, to a linear half-float EXR");
  add_scene_options(cmd, a->scene, a->method, a->no_surface_airlight);
  add_cloud_render_options(cmd, a->clouds);
  add_camera_options(cmd, a->camera);
  cmd->add_option("--jitter", a->jitter, "Ray-march jitter: blue, white or none")->capture_default_str();
  cmd->add_option("--shadow-res", a->shadow_res, "Point-light shadow map size per cube face (sun: twice)")
      ->capture_default_str();
  cmd->add_option("--extinction", a->extinction, "Override the fog's extinction, per metre");
  cmd->add_option("--albedo", a->albedo, "Override the fog's single-scattering albedo, [0, 1]");
  cmd->add_option("--phase", a->phase, "Override the phase function: isotropic, hg:G, schlick:G, rayleigh");
  cmd->add_flag("--hide-bulbs", a->hide_bulbs, "Do not draw the lights' bulbs (as nimbus bench shafts does)");
  cmd->add_option("--preview", a->preview, "Also write a tone-mapped sRGB PNG preview here");
  add_setting_option(cmd, render::Setting::Exposure, a->exposure);
  cmd->add_option("--view-state", a->view_state,
                  "Render a viewer state (nimbus view's Ctrl+S) at full quality, through the viewer's pipeline: --res times the "
                  "state's render scale");
  cmd->add_option("-o,--output", a->output, "Output EXR file")->required();
  cmd->callback([&action, a, cmd] {
    a->scene_given = cmd->count("--scene") > 0;
    a->method_given = cmd->count("--method") > 0;
    action = [a, cmd] { return run_render(*a, *cmd); };
  });
}

}  // namespace nimbus::cli

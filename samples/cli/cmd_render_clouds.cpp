// `nimbus render FILE.vdb | --preset NAME`: clouds by half-angle slicing over a scene (the sky
// by default: ground, sun, haze, sky), or alone; the CPU reference for clouds alone; sequences.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <regex>

#include "cloud_flags.hpp"
#include "frame_range.hpp"
#include "nimbus/app/sequence_path.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/cloud_framing.hpp"
#include "nimbus/render/core/cloud_method.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/scene/daylight.hpp"
#include "nimbus/render/sky/grain_filter.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/frame/frame_renderer.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/memory.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/volume/json_io.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "outputs.hpp"
#include "progress.hpp"
#include "render_clouds.hpp"
#include "render_clouds_plan.hpp"
#include "setting_flags.hpp"
#include "typed_option.hpp"

namespace nimbus::cli {

using app::check_sequence_pattern;
using app::has_frame_field;
using app::sequence_path;
namespace {

// A sequence's file of `frame` (sequence_path.hpp); the name as it is for a single picture.
std::string frame_path(const std::string& pattern, int frame, bool sequence) {
  return sequence ? sequence_path(pattern, frame) : pattern;
}

// The clouds of one frame (library calls): files as they are, turned y-up, presets generated at
// the frame's time, with their progress on stderr.
std::vector<render::CloudVolume> load_clouds(const CloudRenderArgs& a, const std::vector<render::PresetCloud>& presets,
                                             const render::CloudOptics& optics, const FrameRange& range, int frame) {
  const bool sequence = range.sequence;
  std::vector<render::CloudVolume> clouds;
  const render::UpAxis up = render::parse_up_axis(a.up);
  auto memory = a.memory.begin();
  const auto memory_before = [&](std::size_t file) {
    for (; memory != a.memory.end() && memory->position <= file; ++memory)
      clouds.push_back(render::cloud_from_grid(*memory->grid, memory->period_m, optics, memory->name));
  };
  for (std::size_t n = 0; n < a.files.size(); ++n) {
    memory_before(n);
    const std::string& pattern = a.files[n];
    const std::string path = frame_path(pattern, frame, sequence && has_frame_field(pattern));
    render::CloudFileOptions fo;
    fo.level_set_to_fog = a.level_set_to_fog;
    fo.warn = [](const std::string& text) { std::fprintf(stderr, "nimbus: warning: %s\n", text.c_str()); };
    // Each error names the file it is about (some of the reader's do not: "a dense copy of grid
    // 'density' ... exceeds any memory"), keeping its kind and so its exit code.
    const auto named = [&](const std::exception& e) {
      const std::string what = e.what();
      return what.find(path) != std::string::npos ? what : "FILE '" + path + "': " + what;
    };
    try {
      clouds.push_back(render::load_cloud_file(path, a.grid, up, optics, fo));
    } catch (const volume::GridNotFound& e) {
      throw UsageError(std::string("--grid: ") + e.what());  // as nimbus info reports it
    } catch (const OutOfMemoryRequest& e) {
      throw OutOfMemoryRequest(named(e));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(named(e));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(named(e));
    }
  }
  memory_before(a.files.size());
  for (const render::PresetCloud& preset : presets) {
    Progress progress("generating " + preset.name);
    std::mutex m;
    const double time = range.time(frame);
    try {
      clouds.push_back(render::generate_preset_cloud(preset, a.voxel_size, time, optics, [&](double x) {
        std::lock_guard<std::mutex> lock(m);
        progress.update(x);
      }));
    } catch (const OutOfMemoryRequest&) {
      throw;
    } catch (const std::invalid_argument& e) {  // the time moved the cloud or its noise out of range
      throw UsageError("--preset " + preset.name + " at " + time_text(time) + " (--time, --frames/--fps): " + e.what());
    }
  }
  return clouds;
}

// What a frame renders, for an error that arises while rendering it: "clouds.vdb, --preset steam
// (frame 3)".
std::string describe_clouds(const CloudRenderArgs& a, int frame, bool sequence) {
  std::string text;
  for (const std::string& f : a.files)
    text += (text.empty() ? "" : ", ") + frame_path(f, frame, sequence && has_frame_field(f));
  for (const MemoryCloud& m : a.memory) text += (text.empty() ? "" : ", ") + m.name;
  for (const std::string& p : a.presets) text += (text.empty() ? "--preset " : ", --preset ") + p;
  return text + (sequence ? " (frame " + std::to_string(frame) + ")" : "");
}

}  // namespace

// --request FILE: the file's request in place of a still's defaults. CLI11 runs callbacks in the
// order the options were added, so this one comes first and the flags override it. Every value
// in the file is stated, as a flag is given: its method of multiple scattering is --ms-method's
// (a view state's octaves are the viewer's fallback, not a still's).
void add_request_file_option(CLI::App* cmd, CloudRenderArgs& a) {
  cmd->add_option_function<std::string>(
      "--request",
      [&a](const std::string& path) {
        a.request = parse_flag_text("--request", path, [&](const std::string& p) {
          const nlohmann::json doc = volume::read_json_file(p, "render request");
          if (doc.is_object() && (doc.contains("sky") || doc.contains("time")))
            throw UsageError("--request: '" + echo(p) + "' is a view state (it holds a sky and clocks): render it with "
                             "--view-state, or keep its scene, camera, optics and renderer as a request");
          return render::render_request_from_json(doc, "render request '" + p + "'");
        });
        a.request_file = path;
        a.ms_method = a.request.slices.multiple.method;
        for (const render::RenderSetting& s : render::kRenderSettings)
          if (is_cloud_setting(s.id) && s.id != render::Setting::Multiple) a.settings_given.insert(s.id);
      },
      "A render request (JSON: scene, camera, optics, renderer, as a view state holds them; docs/cli.md) in place "
      "of the defaults; the flags given override it");
}

void add_cloud_render_options(CLI::App* cmd, CloudRenderArgs& a) {
  add_request_file_option(cmd, a);
  cmd->add_option("file", a.files, "VDB file(s) of clouds (a %04d pattern with --frames)");
  cmd->add_option("--preset", a.presets, "Cloud preset(s) to generate (nimbus presets)");
  cmd->add_option("--grid", a.grid, "Grid name in the files (default: density, else the first float grid)");
  cmd->add_option("--up-axis", a.up, "Up axis of the files: auto (their up_axis metadata, else y), y or z (flags are always Z up)")
      ->capture_default_str();
  cmd->add_flag("--level-set-to-fog", a.level_set_to_fog,
                "A level set (signed distance) in a file becomes a fog volume: 1 inside, 0 outside (else it is refused)");
  cmd->add_option("--voxel-size", a.voxel_size, "Voxel size of generated presets, metres (default: the preset's)");
  add_frame_options(cmd, a.frame, "name.%04d.exr (presets generated at each frame's time)");
  add_sun_options(cmd, a.sun);
  add_typed_list_option(cmd, "--lamp", a.lamps, [](const std::string& t) { return parse_world_vec3("--lamp", t); },
                        "A lamp on the clouds at X,Y,Z (repeatable; in a scene it joins the scene's point lights, which "
                        "light the clouds too)");
  add_typed_option(cmd, "--lamp-intensity", a.lamp_intensity_w_sr,
                   [](const std::string& t) { return parse_colour("--lamp-intensity", t); },
                   "Radiant intensity of every --lamp, W/sr, V or R,G,B", "100");
  add_typed_option(cmd, "--spot", a.spot_axis, [](const std::string& t) { return std::optional(parse_spot_axis(t)); },
                   "Every --lamp is a spot shining along DX,DY,DZ");
  add_typed_option(cmd, "--spot-cone", a.spot_cone_deg, parse_spot_cone,
                   "The spot's inner,outer cone half-angles, degrees", "20,30");
  add_cloud_setting_options(cmd, a.request, a.settings_given);  // the table's numbers (setting_flags.hpp)
  add_typed_option(cmd, "--shafts", a.request.shafts, render::parse_shaft_method,
                   "The scene's light-shaft method under the clouds (see --method)", kCloudShaftsDefault);
  add_typed_option(cmd, "--cloud-albedo", a.request.optics.albedo,
                   [](const std::string& t) { return parse_colour("--cloud-albedo", t); },
                   "Cloud single-scattering albedo, V or R,G,B", number_text(render::kCloudAlbedo));
  add_typed_option(cmd, "--cloud-phase", a.request.optics.phase, render::parse_cloud_phase,
                   "Cloud phase: isotropic, hg:G or dual:GF,GB,W", render::to_string(render::kCloudPhase));
  add_typed_option(cmd, "--ambient", a.ambient, parse_ambient,
                   "Ambient sky radiance on the clouds, R,G,B or auto (the sky's mean, else 0)", "auto");
  add_typed_option(cmd, "--ms-method", a.ms_method,
                   [](const std::string& t) { return std::optional(render::parse_multiple_scattering_method(t)); },
                   "Multiple-scattering method of the slicer: light-volume (photon-traced scattered light per voxel; "
                   "the default) or octaves (the default when --multiple N > 0 is given alone)");
  cmd->add_option("--ms-seed", a.request.slices.multiple.light_volume.seed,
                  "Light volume: random seed (the same seed gives the same volume)")
      ->capture_default_str();
  cmd->add_flag_callback("--no-jitter", [&a] { a.request.slices.jitter = false; },
                         "Do not jitter the samples within their slices");
  cmd->add_flag_callback("--no-grain-filter", [&a] { a.request.grain_filter.on = false; },
                         "Slices: keep the jitter's grain (by default a still of fewer than 32 samples is filtered of it, guided by depth)");
  cmd->add_option("--spp", a.spp, "--method pathtrace: samples per pixel; --view-state: progressive samples averaged (sub-pixel offsets, shifted jitter: the slicer's grain goes), default 1")->capture_default_str();
  cmd->add_option("--bounces", a.bounces, "--method pathtrace: scattering events per path at most (1: single scattering)")
      ->capture_default_str();
  cmd->add_option("--seed", a.seed, "--method pathtrace: random seed (the same seed gives the same image)")
      ->capture_default_str();
}

namespace {

// Every file of every frame: outputs writable, none of them an input, before any work.
void check_cloud_render_files(const CloudRenderArgs& a, const CloudRenderPlan& plan, const std::string& output,
                              const std::string& preview) {
  const FrameRange& range = plan.range;
  std::vector<PathArg> outputs;
  RunInputs inputs;
  for (const render::PresetCloud& preset : plan.presets) inputs.cloud(preset.params, "--preset " + preset.name + " cloud");
  for (int frame = range.first; frame <= range.last; ++frame) {
    if (!output.empty()) outputs.push_back({"-o", frame_path(output, frame, range.sequence)});
    if (!preview.empty()) outputs.push_back({"--preview", frame_path(preview, frame, range.sequence)});
    for (const std::string& pattern : a.files)
      inputs.file("FILE", frame_path(pattern, frame, range.sequence && has_frame_field(pattern)));
  }
  if (!a.request_file.empty()) inputs.file("--request", a.request_file);
  for (const PathArg& in : inputs.paths()) refuse_special_file(in.path, in.flag);
  check_outputs(outputs, inputs);
}

// The camera of a frame: framed on its clouds unless the flags or a request file place it, or the scene is made for
// its gas (steam-lamp: its camera is aimed where the steam rises).
render::Camera frame_camera(const CloudRenderArgs& a, const CloudRenderPlan& plan, const CameraArgs& camera_args,
                            const std::vector<render::CloudVolume>& clouds, int frame) {
  const std::optional<render::Scene>& scene = plan.frame.scene;
  render::Camera camera = plan.frame.camera;
  const bool framed = camera_args.eye.empty() && camera_args.look_at.empty() && a.request_file.empty() &&
                      !(scene && scene->cloud_extinction_per_m);
  if (framed) {
    CameraArgs size_only;
    size_only.res = camera_args.res;
    size_only.fov_deg = camera_args.fov_deg;
    camera = render::frame_clouds(apply_camera_args(size_only, plan.frame.camera), clouds,
                                  scene && scene->ground.has_value());
  }
  try {
    camera = apply_camera_args(camera_args, camera);
  } catch (const UsageError& e) {
    // A camera framed on clouds no camera can frame (a file whose voxels are 1e300 m) fails
    // here: the file is at fault, not the flags.
    if (!framed || !camera_args.up.empty()) throw;
    throw std::runtime_error("framing the camera on " + describe_clouds(a, frame, plan.range.sequence) + ": " + e.what());
  }
  const double repeat_to_m = plan.frame.settings.slices.repeat_to_m;
  if (!camera_args.eye.empty() || !camera_args.look_at.empty() || !a.request_file.empty() || repeat_to_m > 0.0)
    camera = render::fit_far_plane(camera, clouds, repeat_to_m);
  return camera;
}

// Writes a frame's image (and preview), with the sequence's metadata, and says what it drew.
void write_cloud_frame(render::Image& image, const CloudRenderPlan& plan, const render::Camera& camera,
                       const render::FrameStats& stats, std::size_t n_clouds, double seconds, int frame,
                       const std::string& output, const std::string& preview, std::optional<double> exposure) {
  const FrameRange& range = plan.range;
  if (range.sequence) {
    image.metadata["frame"] = std::to_string(frame);
    image.metadata["fps"] = std::to_string(range.fps);
    image.metadata["start_frame"] = std::to_string(range.start_frame);
  }
  const std::string out = frame_path(output, frame, range.sequence);
  render::PreviewOptions po;
  if (!preview.empty()) po.exposure_stops = exposure ? *exposure : render::auto_exposure_stops(image);
  write_image_files(out, preview.empty() ? "" : frame_path(preview, frame, range.sequence), image, po);
  warn_half_float_clipping(image, out, "--lamp-intensity, --ambient or the scene's lights");
  std::fprintf(stderr, "%s: %zu cloud(s) over %s, %dx%d, %s, %.2f s on %s%s%s\n", out.c_str(), n_clouds,
               plan.frame.scene ? plan.frame.scene->name.c_str() : "nothing", camera.width, camera.height, plan.method.c_str(),
               seconds, stats.device.c_str(), stats.summary.empty() ? "" : "; ", stats.summary.c_str());
}

}  // namespace

int run_render_clouds(const CloudRenderArgs& a, const std::string& scene_name, bool scene_given,
                      const std::string& method_text, bool method_given, const CameraArgs& camera_args,
                      const std::string& output, const std::string& preview, std::optional<double> exposure,
                      const FrameSink& sink) {
  // Flags first, then every file: every usage error before any work (render_clouds_plan.cpp).
  CloudRenderPlan plan =
      plan_cloud_render(a, scene_name, scene_given, method_text, method_given, output, preview, exposure);
  check_cloud_render_files(a, plan, output, preview);
  check_camera_flags(camera_args);  // applied per frame, once its clouds are loaded
  checks_done();

  render::FrameSettings& fs = plan.frame.settings;
  std::unique_ptr<render::GlContext> gl;
  if (fs.method == render::CloudMethod::Slices) {
    try {
      gl = render::GlContext::create_headless();
    } catch (const render::GlUnavailable& e) {
      throw std::runtime_error(std::string("method slices needs OpenGL: ") + e.what());
    }
  }
  std::unique_ptr<Progress> reference_progress;
  std::mutex progress_mutex;
  fs.reference.progress = [&](double x) {
    std::lock_guard<std::mutex> lock(progress_mutex);
    if (reference_progress) reference_progress->update(x);
  };
  fs.path_tracer.progress = fs.reference.progress;
  render::FrameRenderer renderer(plan.frame);

  const FrameRange& range = plan.range;
  for (int frame = range.first; frame <= range.last; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    renderer.set_clouds(load_clouds(a, plan.presets, plan.frame.optics, range, frame));
    const render::Camera camera = frame_camera(a, plan, camera_args, renderer.clouds(), frame);
    if (render::is_cpu_method(fs.method))
      reference_progress = std::make_unique<Progress>("cloud " + plan.method +
                                                      (range.sequence ? " frame " + std::to_string(frame) : ""));
    render::FrameStats stats;
    render::Image image;
    try {
      render::PixelDepths depths;  // to guide the grain filter
      image = naming_gpu_memory("--res", camera.width, camera.height, [&] { return renderer.render(camera, &stats, &depths); });
      // One jittered frame of slices holds the jitter's grain (grain_filter.hpp).
      render::GrainFilter grain;
      grain.on = a.request.grain_filter.on;
      image = render::still_picture(image, 1, depths, grain, fs.method == render::CloudMethod::Slices && fs.slices.jitter);
    } catch (const std::invalid_argument& e) {
      // A stage refused what it computed (a NaN pixel): the flags were checked, so say which
      // input it was rendering, and that it is a failure of the render, not of the usage.
      throw std::runtime_error("rendering " + describe_clouds(a, frame, range.sequence) + ": " + e.what());
    }
    reference_progress.reset();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (sink)
      sink(image, frame);
    else
      write_cloud_frame(image, plan, camera, stats, renderer.clouds().size(), seconds, frame, output, preview,
                        exposure || a.request_file.empty() ? exposure : std::optional(a.request.exposure_stops));
  }
  return 0;
}

}  // namespace nimbus::cli

// `nimbus render FILE.vdb | --preset NAME`: clouds by half-angle slicing over a scene (the sky
// by default: ground, sun, haze, sky), or alone; the CPU reference for clouds alone; sequences.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <regex>

#include "frame_range.hpp"
#include "sequence_path.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/cloud_framing.hpp"
#include "nimbus/render/core/cloud_method.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "nimbus/render/core/daylight.hpp"
#include "nimbus/render/core/scene.hpp"
#include "nimbus/render/frame/frame_renderer.hpp"
#include "nimbus/render/gl/context.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/memory.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "outputs.hpp"
#include "progress.hpp"
#include "render_clouds.hpp"

namespace nimbus::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A sequence's file of `frame` (sequence_path.hpp); the name as it is for a single picture.
std::string frame_path(const std::string& pattern, int frame, bool sequence) {
  return sequence ? sequence_path(pattern, frame) : pattern;
}

glm::dvec3 parse_colour(const std::string& flag, const std::string& text) {
  if (text.find(',') == std::string::npos) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || !std::isfinite(v)) throw UsageError(flag + ": '" + text + "' must be V or R,G,B");
    if (std::abs(v) > kMaxFlagMagnitude) throw UsageError(flag + ": '" + text + "' must be within +-1e12");
    return glm::dvec3(v);
  }
  return parse_vec3(flag, text);
}

// The clouds of one frame (library calls): files as they are, turned y-up, presets generated at
// the frame's time, with their progress on stderr.
std::vector<render::CloudVolume> load_clouds(const CloudRenderArgs& a, const std::vector<render::PresetCloud>& presets,
                                             const render::CloudOptics& optics, const FrameRange& range, int frame) {
  const bool sequence = range.sequence;
  std::vector<render::CloudVolume> clouds;
  const render::UpAxis up = render::parse_up_axis(a.up);
  for (const std::string& pattern : a.files) {
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
  for (const std::string& p : a.presets) text += (text.empty() ? "--preset " : ", --preset ") + p;
  return text + (sequence ? " (frame " + std::to_string(frame) + ")" : "");
}

}  // namespace

void add_cloud_render_options(CLI::App* cmd, CloudRenderArgs& a) {
  cmd->add_option("file", a.files, "VDB file(s) of clouds (a %04d pattern with --frames)");
  cmd->add_option("--preset", a.presets, "Cloud preset(s) to generate (nimbus presets)");
  cmd->add_option("--grid", a.grid, "Grid name in the files (default: density, else the first float grid)");
  cmd->add_option("--up-axis", a.up, "Up axis of the files: auto (their up_axis metadata, else y), y or z")
      ->capture_default_str();
  cmd->add_flag("--level-set-to-fog", a.level_set_to_fog,
                "A level set (signed distance) in a file becomes a fog volume: 1 inside, 0 outside (else it is refused)");
  cmd->add_option("--voxel-size", a.voxel_size, "Voxel size of generated presets, metres (default: the preset's)");
  add_frame_options(cmd, a.frame, "name.%04d.exr (presets generated at each frame's time)");
  cmd->add_option("--sun", a.sun, "Direction towards the sun X,Y,Z (replaces the scene's; adds one if it has none)");
  cmd->add_option("--lamp", a.lamps,
                  "A lamp on the clouds at X,Y,Z (repeatable; in a scene it joins the scene's point lights, which light "
                  "the clouds too)");
  cmd->add_option("--lamp-intensity", a.lamp_intensity, "Radiant intensity of every --lamp, W/sr, V or R,G,B")
      ->capture_default_str();
  cmd->add_option("--spot", a.spot, "Every --lamp is a spot shining along DX,DY,DZ (--scene none only)");
  cmd->add_option("--spot-cone", a.spot_cone, "The spot's inner,outer cone half-angles, degrees")->capture_default_str();
  cmd->add_option("--max-lights", a.max_lights, "Lights the slicer draws, one pass each: the strongest at the clouds, 1-8")
      ->capture_default_str();
  cmd->add_option("--slices", a.slices, "Half-angle slices")->capture_default_str();
  cmd->add_option("--light-res", a.light_res, "Light buffer size, texels per side")->capture_default_str();
  cmd->add_option("--cloud-shadow-res", a.shadow_map_res, "Texels per side of the clouds' shadow on the scene")
      ->capture_default_str();
  cmd->add_option("--shafts", a.shafts, "The scene's light-shaft method under the clouds (see --method)")
      ->capture_default_str();
  cmd->add_option("--cloud-extinction", a.cloud_extinction, "Cloud extinction per unit density, per metre (default 0.04)");
  cmd->add_option("--cloud-albedo", a.cloud_albedo, "Cloud single-scattering albedo, V or R,G,B (default 0.99)");
  cmd->add_option("--cloud-phase", a.cloud_phase, "Cloud phase: isotropic, hg:G or dual:GF,GB,W")->capture_default_str();
  cmd->add_option("--ambient", a.ambient, "Ambient sky radiance on the clouds, R,G,B or auto (the sky's mean, else 0)")
      ->capture_default_str();
  cmd->add_option("--multiple", a.multiple,
                  "Multiple scattering: 0 = single scattering; octaves 1-3 (the octaves method, unless --ms-method "
                  "light-volume, which takes 1 = on)");
  cmd->add_option("--ms-method", a.ms_method,
                  "Multiple-scattering method of the slicer: light-volume (photon-traced scattered light per voxel; "
                  "the default) or octaves (the default when --multiple N > 0 is given alone)");
  cmd->add_option("--ms-grid", a.ms_grid, "Light volume: cells along the clouds' longest axis at least, 4-192 (finer where its photons allow: about 1000 a cell)")->capture_default_str();
  cmd->add_option("--ms-photons", a.ms_photons, "Light volume: photons from the sun, 1-268435456")->capture_default_str();
  cmd->add_option("--ms-lobes", a.ms_lobes, "Light volume: scattering orders kept as lobes about the sun, 0-2 (0: harmonics alone)")
      ->capture_default_str();
  cmd->add_option("--ms-seed", a.ms_seed, "Light volume: random seed (the same seed gives the same volume)")
      ->capture_default_str();
  cmd->add_option("--blur", a.blur_deg, "Forward-scattering blur cone half-angle, degrees (0: off)")->capture_default_str();
  cmd->add_flag("--no-jitter", a.no_jitter, "Do not jitter the samples within their slices");
  cmd->add_option("--ms-occlusion", a.ms_occlusion, "Multiple-scattering octaves: extinction scale a per octave, (0, 1]")
      ->capture_default_str();
  cmd->add_option("--ms-contribution", a.ms_contribution, "Multiple-scattering octaves: radiance scale b per octave, [0, 1]")
      ->capture_default_str();
  cmd->add_option("--ms-eccentricity", a.ms_eccentricity, "Multiple-scattering octaves: phase asymmetry scale c per octave, [0, 1]")
      ->capture_default_str();
  cmd->add_option("--spp", a.spp, "--method pathtrace: samples per pixel")->capture_default_str();
  cmd->add_option("--bounces", a.bounces, "--method pathtrace: scattering events per path at most (1: single scattering)")
      ->capture_default_str();
  cmd->add_option("--seed", a.seed, "--method pathtrace: random seed (the same seed gives the same image)")
      ->capture_default_str();
}

// --multiple, --ms-method and the light volume's flags as the slicer's MultipleScattering; each
// bad value a UsageError naming its flag. Without the sun the light volume (photons from the sun)
// is not the default.
// UsageError "<flag>: <why>" when `flag` was given but what it qualifies is not in effect (it
// would be ignored without a word).
static void refuse_if_given_without(const CloudRenderArgs& a, const std::string& flag, bool applies, const std::string& why) {
  if (a.given.count(flag) && !applies) throw UsageError(flag + ": " + why);
}

static render::MultipleScattering multiple_scattering_of(const CloudRenderArgs& a, bool sun) {
  render::MultipleScattering ms;
  if (a.ms_method.empty()) {
    ms.method = (a.multiple && *a.multiple > 0) || !sun ? render::MultipleScatteringMethod::Octaves
                                                        : render::MultipleScatteringMethod::LightVolume;
  } else {
    try {
      ms.method = render::parse_multiple_scattering_method(a.ms_method);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--ms-method: ") + e.what());
    }
  }
  if (a.multiple && (*a.multiple < 0 || *a.multiple > 3))
    throw UsageError("--multiple: must be in [0, 3], got " + std::to_string(*a.multiple));
  if (ms.method == render::MultipleScatteringMethod::LightVolume) {
    if (!sun) throw UsageError("--ms-method: light-volume traces photons from the sun, and nothing gives one (--sun)");
    if (a.multiple && *a.multiple > 1)
      throw UsageError("--multiple: --ms-method light-volume takes 0 (single scattering) or 1 (on), got " +
                       std::to_string(*a.multiple));
    if (a.multiple && *a.multiple == 0) ms.method = render::MultipleScatteringMethod::Octaves;  // octaves 0: single
  } else {
    ms.octaves = a.multiple.value_or(0);
  }
  const bool light_volume = ms.method == render::MultipleScatteringMethod::LightVolume;
  for (const char* flag : {"--ms-grid", "--ms-photons", "--ms-lobes", "--ms-seed"})
    refuse_if_given_without(a, flag, light_volume,
                            "applies to the light volume (--ms-method light-volume), and the multiple scattering here is "
                            "the octaves method");
  for (const char* flag : {"--ms-occlusion", "--ms-contribution", "--ms-eccentricity"})
    refuse_if_given_without(a, flag, !light_volume && ms.octaves > 0,
                            "applies to the octaves of multiple scattering (--multiple 1-3 with --ms-method octaves), "
                            "which this render does not use");
  if (a.ms_grid < 4 || a.ms_grid > 192)
    throw UsageError("--ms-grid: must be in [4, 192] cells, got " + std::to_string(a.ms_grid));
  if (a.ms_photons < 1 || a.ms_photons > (int64_t{1} << 28))
    throw UsageError("--ms-photons: must be in [1, 268435456], got " + std::to_string(a.ms_photons));
  ms.light_volume.resolution = a.ms_grid;
  ms.light_volume.photons = a.ms_photons;
  if (a.ms_lobes < 0 || a.ms_lobes > 2) throw UsageError("--ms-lobes: must be in [0, 2], got " + std::to_string(a.ms_lobes));
  ms.light_volume.lobe_orders = a.ms_lobes;
  ms.light_volume.seed = a.ms_seed;
  auto check = [](double v, bool ok, const char* flag, const char* range) {
    if (!std::isfinite(v) || !ok) throw UsageError(std::string(flag) + ": must be in " + range + ", got " + std::to_string(v));
  };
  check(a.ms_occlusion, a.ms_occlusion > 0.0 && a.ms_occlusion <= 1.0, "--ms-occlusion", "(0, 1]");
  check(a.ms_contribution, a.ms_contribution >= 0.0 && a.ms_contribution <= 1.0, "--ms-contribution", "[0, 1]");
  check(a.ms_eccentricity, a.ms_eccentricity >= 0.0 && a.ms_eccentricity <= 1.0, "--ms-eccentricity", "[0, 1]");
  ms.occlusion = a.ms_occlusion;
  ms.contribution = a.ms_contribution;
  ms.eccentricity = a.ms_eccentricity;
  return ms;
}

int run_render_clouds(const CloudRenderArgs& a, const std::string& scene_name, bool scene_given,
                      const std::string& method_text, bool method_given, const CameraArgs& camera_args,
                      const std::string& output, const std::string& preview, std::optional<double> exposure) {
  // Flags first: every usage error before any work.
  const std::string method = method_given ? method_text : "slices";
  render::CloudMethod cloud_method;
  try {
    cloud_method = render::parse_cloud_method(method);
  } catch (const std::invalid_argument&) {
    throw UsageError("--method: '" + method + "' is not a cloud method (slices, reference or pathtrace)");
  }
  const std::string scene_choice = scene_given ? scene_name : "sky";
  const bool no_scene = scene_choice == "none";
  if (render::is_cpu_method(cloud_method) && !no_scene)
    throw UsageError("--method " + method + " renders clouds alone, without a scene: add --scene none");
  render::Scene scene;
  if (!no_scene) {
    try {
      scene = render::make_scene(scene_choice);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--scene: ") + e.what() + " (or none)");
    }
  }
  if (a.up != "auto" && a.up != "y" && a.up != "z") throw UsageError("--up-axis: '" + a.up + "' must be auto, y or z");
  if (a.voxel_size && !(std::isfinite(*a.voxel_size) && *a.voxel_size > 0))
    throw UsageError("--voxel-size: must be finite and > 0 (metres)");
  const FrameRange range = parse_frames(a.frame);
  const int first = range.first, last = range.last;
  const bool sequence = range.sequence;
  if (range.whole_last > range.whole_first && a.presets.empty() &&
      std::none_of(a.files.begin(), a.files.end(), [](const std::string& f) { return f.find('%') != std::string::npos; }))
    throw UsageError("--frames: every frame would render the same FILE with the same camera; give a sequence "
                     "name.%04d.vdb, or --preset (generated at each frame's time)");
  check_sequence_pattern("-o", output);
  if (!preview.empty()) check_sequence_pattern("--preview", preview);
  for (const std::string& f : a.files) check_sequence_pattern("file", f);
  if (!sequence)  // a frame field is filled only in a sequence; alone it would name a file "%04d"
    for (const auto& [flag, p] : {std::pair<std::string, std::string>{"-o", output}, {"--preview", preview}})
      if (has_frame_field(p)) throw UsageError(flag + ": '" + echo(p) + "' holds a frame field but no --frames was given");
  check_exposure(exposure);
  if (a.shadow_map_res < 16 || a.shadow_map_res > 8192) throw UsageError("--cloud-shadow-res: must be in [16, 8192]");

  render::CloudOptics optics;
  if (a.cloud_extinction) {
    if (!(std::abs(*a.cloud_extinction) <= kMaxFlagMagnitude))
      throw UsageError("--cloud-extinction: must be at most 1e12 per metre (per unit density)");
    optics.extinction_per_m = *a.cloud_extinction;
  } else if (scene.cloud_extinction_per_m) {
    optics.extinction_per_m = *scene.cloud_extinction_per_m;  // the scene's gas (steam-lamp: a cup's steam)
  }
  if (!a.cloud_albedo.empty()) optics.albedo = parse_colour("--cloud-albedo", a.cloud_albedo);
  try {
    optics.phase = render::parse_cloud_phase(a.cloud_phase);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--cloud-phase: ") + e.what());
  }
  if (a.ambient == "auto") {
    optics.ambient_radiance = scene.sky ? render::sky_mean_radiance(*scene.sky) : glm::dvec3(0.0);
  } else {
    optics.ambient_radiance = parse_colour("--ambient", a.ambient);
  }
  try {
    render::validate(optics);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--cloud-extinction/--cloud-albedo/--ambient: ") + e.what());
  }

  // The lights: the sun (given, or the scene's) and the lamps (given, and the scene's).
  std::vector<render::CloudLight> lights;
  for (const std::string& text : a.lamps) {
    const glm::dvec3 at = parse_vec3("--lamp", text);
    lights.push_back(render::point_light(at, parse_colour("--lamp-intensity", a.lamp_intensity)));
  }
  refuse_if_given_without(a, "--lamp-intensity", !a.lamps.empty(), "it sets the --lamp lights' intensity, and none was given");
  refuse_if_given_without(a, "--spot-cone", !a.spot.empty(), "it shapes the --spot cone, and no --spot was given");
  for (const char* flag : {"--spp", "--bounces", "--seed"})
    refuse_if_given_without(a, flag, cloud_method == render::CloudMethod::PathTrace, "applies to --method pathtrace only");
  if (!a.spot.empty()) {
    if (a.lamps.empty()) throw UsageError("--spot: it shapes the --lamp lights, and none was given");
    if (!no_scene) throw UsageError("--spot: a scene's lamps shine every way; spots light clouds alone (--scene none)");
    const glm::dvec3 axis = parse_vec3("--spot", a.spot);
    const std::size_t comma = a.spot_cone.find(',');
    const std::optional<double> inner = comma == std::string::npos ? std::nullopt : parse_double(a.spot_cone.substr(0, comma));
    const std::optional<double> outer = comma == std::string::npos ? std::nullopt : parse_double(a.spot_cone.substr(comma + 1));
    if (!inner || !outer || !(*inner > 0.0) || !(*inner <= *outer) || !(*outer <= 180.0))
      throw UsageError("--spot-cone: '" + a.spot_cone + "' must be INNER,OUTER degrees with 0 < INNER <= OUTER <= 180");
    for (render::CloudLight& l : lights) {
      l.spot_axis = axis;
      l.spot_inner_rad = *inner * kPi / 180.0;
      l.spot_outer_rad = *outer * kPi / 180.0;
    }
  }
  for (const render::CloudLight& l : lights) {
    try {
      render::validate(l);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--lamp/--lamp-intensity/--spot: ") + e.what());
    }
  }
  render::CloudLight light;
  bool sun = false;
  if (!a.sun.empty()) {
    sun = true;
    light.direction_to_light = parse_vec3("--sun", a.sun);
    if (glm::length(light.direction_to_light) == 0.0) throw UsageError("--sun: the direction must not be zero");
    if (!no_scene) {
      if (!scene.sun) scene.sun = render::SunLight{};
      scene.sun->direction_to_sun = light.direction_to_light;
      if (scene.sky && scene.sky->atmosphere) {
        // The physical sky follows the sun: its colour, the sky behind, the light on the clouds.
        try {
          const render::Daylight d = render::daylight(light.direction_to_light, scene.sky->atmosphere->view.altitude_m);
          scene.sun->irradiance_w_m2 = d.cloud_sun_irradiance_w_m2;
          scene.sky = d.sky;
        } catch (const std::invalid_argument& e) {
          throw UsageError(std::string("--sun: ") + e.what());
        }
      }
      light.irradiance_w_m2 = scene.sun->irradiance_w_m2;
    }
  } else if (!no_scene && scene.sun) {
    sun = true;
    light.direction_to_light = scene.sun->direction_to_sun;
    light.irradiance_w_m2 = scene.sun->irradiance_w_m2;
  } else if (!no_scene && scene.point_lights.empty() && lights.empty()) {
    throw UsageError("--sun: the clouds need the sun or a lamp, and scene '" + scene.name + "' has neither; give --sun X,Y,Z or --lamp X,Y,Z");
  } else if (no_scene && lights.empty()) {
    sun = true;  // clouds alone: the default sun
  }
  if (sun) lights.insert(lights.begin(), light);
  if (a.ambient == "auto" && scene.sky) optics.ambient_radiance = render::sky_mean_radiance(*scene.sky);  // after --sun moved it

  render::CloudSliceSettings settings;
  settings.slices = a.slices;
  settings.light_res = a.light_res;
  settings.jitter = !a.no_jitter;
  settings.ambient = true;
  settings.blur_cone_rad = a.blur_deg * kPi / 180.0;
  settings.multiple = multiple_scattering_of(a, sun);
  settings.max_lights = a.max_lights;
  settings.multiple.occlusion = a.ms_occlusion;
  settings.multiple.contribution = a.ms_contribution;
  settings.multiple.eccentricity = a.ms_eccentricity;
  try {
    render::validate(settings);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--slices/--light-res/--multiple/--blur/--max-lights: ") + e.what());
  }
  render::ShaftMethod shafts;
  if (!no_scene) {
    try {
      shafts = render::parse_shaft_method(a.shafts);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--shafts: ") + e.what());
    }
    if (shafts.kind == render::ShaftMethod::Kind::Reference)
      throw UsageError("--shafts: the scene under GPU clouds needs a GPU method, not reference");
  }
  render::Camera base = no_scene ? render::Camera{} : scene.camera;
  if (no_scene) {
    base.width = 512;
    base.height = 512;
    base.fov_deg = 44.8;  // vdb_render's default
  }

  std::vector<render::PresetCloud> presets;
  for (const std::string& name : a.presets) {
    try {
      presets.push_back(render::load_preset_cloud(name));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--preset: ") + e.what());
    }
  }

  render::FrameSettings fs;
  fs.method = cloud_method;
  fs.slices = settings;
  fs.shafts = shafts;
  fs.cloud_shadow_res = a.shadow_map_res;
  fs.shaft_settings.surface_airlight = a.surface_airlight;
  fs.path_tracer.samples_per_pixel = a.spp;
  fs.path_tracer.max_bounces = a.bounces;
  fs.path_tracer.seed = a.seed;
  try {
    render::validate(fs.path_tracer);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--spp/--bounces: ") + e.what());
  }
  if (fs.method == render::CloudMethod::PathTrace && (lights.size() != 1 || lights[0].kind != render::CloudLightKind::Sun))
    throw UsageError("--lamp: --method pathtrace traces the sun only");

  // Every file of every frame: outputs writable, none of them an input, before any work.
  std::vector<PathArg> outputs, inputs;
  for (int frame = first; frame <= last; ++frame) {
    outputs.push_back({"-o", frame_path(output, frame, sequence)});
    if (!preview.empty()) outputs.push_back({"--preview", frame_path(preview, frame, sequence)});
    for (const std::string& pattern : a.files)
      inputs.push_back({"FILE", frame_path(pattern, frame, sequence && has_frame_field(pattern))});
  }
  for (const PathArg& in : inputs) refuse_special_file(in.path, in.flag);
  check_outputs(outputs, inputs);
  checks_done();

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
  render::FrameRenderer renderer(no_scene ? std::nullopt : std::optional<render::Scene>(scene), lights, fs);

  for (int frame = first; frame <= last; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    renderer.set_clouds(load_clouds(a, presets, optics, range, frame));
    const std::size_t n_clouds = renderer.clouds().size();
    // Camera: framed on the clouds unless the flags place it, or the scene is made for its gas
    // (steam-lamp: its camera is aimed where the steam rises).
    render::Camera camera = base;
    const bool framed = camera_args.eye.empty() && camera_args.look_at.empty() && !scene.cloud_extinction_per_m;
    if (framed) {
      CameraArgs size_only;
      size_only.res = camera_args.res;
      size_only.fov_deg = camera_args.fov_deg;
      camera = render::frame_clouds(apply_camera_args(size_only, base), renderer.clouds(),
                                    !no_scene && scene.ground.has_value());
    }
    try {
      camera = apply_camera_args(camera_args, camera);
    } catch (const UsageError& e) {
      // A camera framed on clouds no camera can frame (a file whose voxels are 1e300 m) fails
      // here: the file is at fault, not the flags.
      if (!framed || !camera_args.up.empty()) throw;
      throw std::runtime_error("framing the camera on " + describe_clouds(a, frame, sequence) + ": " + e.what());
    }
    if (!camera_args.eye.empty() || !camera_args.look_at.empty()) camera = render::fit_far_plane(camera, renderer.clouds());

    if (render::is_cpu_method(fs.method))
      reference_progress = std::make_unique<Progress>("cloud " + method + (sequence ? " frame " + std::to_string(frame) : ""));
    render::FrameStats stats;
    render::Image image;
    try {
      image = naming_gpu_memory("--res", camera.width, camera.height, [&] { return renderer.render(camera, &stats); });
    } catch (const std::invalid_argument& e) {
      // A stage refused what it computed (a NaN pixel): the flags were checked, so say which
      // input it was rendering, and that it is a failure of the render, not of the usage.
      throw std::runtime_error("rendering " + describe_clouds(a, frame, sequence) + ": " + e.what());
    }
    reference_progress.reset();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (sequence) {
      image.metadata["frame"] = std::to_string(frame);
      image.metadata["fps"] = std::to_string(range.fps);
      image.metadata["start_frame"] = std::to_string(range.start_frame);
    }
    const std::string out = frame_path(output, frame, sequence);
    render::PreviewOptions po;
    if (!preview.empty()) po.exposure_stops = exposure ? *exposure : render::auto_exposure_stops(image);
    write_image_files(out, preview.empty() ? "" : frame_path(preview, frame, sequence), image, po);
    warn_half_float_clipping(image, out, "--lamp-intensity, --ambient or the scene's lights");
    std::fprintf(stderr, "%s: %zu cloud(s) over %s, %dx%d, %s, %.2f s on %s%s%s\n", out.c_str(), n_clouds,
                 no_scene ? "nothing" : scene.name.c_str(), camera.width, camera.height, method.c_str(), seconds,
                 stats.device.c_str(), stats.summary.empty() ? "" : "; ", stats.summary.c_str());
  }
  return 0;
}

}  // namespace nimbus::cli

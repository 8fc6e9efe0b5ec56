// The stages that turn `nimbus render`'s cloud flags into a plan (render_clouds_plan.hpp).
#include "render_clouds_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "frame_range.hpp"
#include "nimbus/app/sequence_path.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/render/scene/sun_setup.hpp"
#include "nimbus/volume/voxel_size.hpp"
#include "outputs.hpp"
#include "setting_flags.hpp"

namespace nimbus::cli {

using app::check_sequence_pattern;
using app::has_frame_field;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLampBulbRadiusM = 0.05;  // a --lamp's bulb, seen in a scene

// UsageError "<flag>: <why>" when `flag` was given but what it qualifies is not in effect (it
// would be ignored without a word).
void refuse_if_given_without(const CloudRenderArgs& a, const std::string& flag, bool applies, const std::string& why) {
  if (a.given.count(flag) && !applies) throw UsageError(flag + ": " + why);
}

// The request's multiple scattering (--multiple, the light volume's and the octaves' flags) with
// its method chosen by --ms-method, else by what was given; each flag given where its method is
// not in effect is a UsageError naming it. Without the sun the light volume (photons from the
// sun) is not the default.
render::MultipleScattering multiple_scattering_of(const CloudRenderArgs& a, bool sun) {
  render::MultipleScattering ms = a.request.slices.multiple;
  const std::optional<int> multiple =
      a.settings_given.count(render::Setting::Multiple) ? std::optional(ms.octaves) : std::nullopt;
  if (!a.ms_method) {
    ms.method = (multiple && *multiple > 0) || !sun ? render::MultipleScatteringMethod::Octaves
                                                    : render::MultipleScatteringMethod::LightVolume;
  } else {
    ms.method = *a.ms_method;
  }
  if (ms.method == render::MultipleScatteringMethod::LightVolume) {
    if (!sun) throw UsageError("--ms-method: light-volume traces photons from the sun, and nothing gives one (--sun)");
    if (multiple && *multiple > 1)
      throw UsageError("--multiple: --ms-method light-volume takes 0 (single scattering) or 1 (on), got " +
                       std::to_string(*multiple));
    ms.octaves = render::MultipleScattering{}.octaves;  // --multiple 1 here means on, not an octave
    if (multiple && *multiple == 0) ms.method = render::MultipleScatteringMethod::Octaves;  // octaves 0: single
  }
  const bool light_volume = ms.method == render::MultipleScatteringMethod::LightVolume;
  for (const char* flag : {"--ms-grid", "--ms-photons", "--ms-lobes", "--ms-diffusion-depth", "--ms-similarity-depth", "--ms-seed"})
    refuse_if_given_without(a, flag, light_volume,
                            "applies to the light volume (--ms-method light-volume), and the multiple scattering here is "
                            "the octaves method");
  for (const char* flag : {"--ms-occlusion", "--ms-contribution", "--ms-eccentricity"})
    refuse_if_given_without(a, flag, !light_volume && ms.octaves > 0,
                            "applies to the octaves of multiple scattering (--multiple 1-3 with --ms-method octaves), "
                            "which this render does not use");
  return ms;
}

// Stage 1: the method (slices, reference, pathtrace) and the scene under the clouds.
void plan_method_and_scene(CloudRenderPlan& p, const CloudRenderArgs& a, const std::string& scene_name, bool scene_given,
                           const std::string& method_text, bool method_given) {
  p.method = method_given ? method_text : "slices";
  try {
    p.cloud_method = render::parse_cloud_method(p.method);
  } catch (const std::invalid_argument&) {
    throw UsageError("--method: '" + p.method + "' is not a cloud method (slices, reference or pathtrace)");
  }
  const std::string scene_choice = scene_given ? scene_name : a.request.scene;  // "sky" unless a request file says
  const bool no_scene = scene_choice == "none";
  if (render::is_cpu_method(p.cloud_method) && !no_scene)
    throw UsageError("--method " + p.method + " renders clouds alone, without a scene: add --scene none");
  if (!no_scene) {
    try {
      p.frame.scene = render::make_scene(scene_choice);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--scene: ") + e.what() + " (or none)");
    }
  }
}

// Stage 2: the inputs' reading flags, the frames, and the names of every file (patterns checked).
void plan_frames_and_names(CloudRenderPlan& p, const CloudRenderArgs& a, const std::string& output,
                           const std::string& preview, std::optional<double> exposure) {
  if (a.up != "auto" && a.up != "y" && a.up != "z") throw UsageError("--up-axis: '" + a.up + "' must be auto, y or z");
  if (a.voxel_size) {
    try {
      volume::check_voxel_size(*a.voxel_size, "--voxel-size");  // the one range of voxel sizes
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  p.range = parse_frames(a.frame);
  // A file's clouds are the same at any time: only presets are generated at --time (the picture
  // of FILE.vdb --time 1e300 was the one of time 0, to the byte).
  if (a.frame.time && a.presets.empty())
    throw UsageError("--time: FILE clouds are the same at any time (a file holds one moment); --time applies to --preset "
                     "clouds, generated at that time");
  if (p.range.whole_last > p.range.whole_first && a.presets.empty() &&
      std::none_of(a.files.begin(), a.files.end(), [](const std::string& f) { return f.find('%') != std::string::npos; }))
    throw UsageError("--frames: every frame would render the same FILE with the same camera; give a sequence "
                     "name.%04d.vdb, or --preset (generated at each frame's time)");
  if (!output.empty()) check_sequence_pattern("-o", output);  // empty: frames go to a sink (render_clouds.hpp)
  if (!preview.empty()) check_sequence_pattern("--preview", preview);
  for (const std::string& f : a.files) check_sequence_pattern("file", f);
  if (!p.range.sequence)  // a frame field is filled only in a sequence; alone it would name a file "%04d"
    for (const auto& [flag, name] : {std::pair<std::string, std::string>{"-o", output}, {"--preview", preview}})
      if (has_frame_field(name)) throw UsageError(flag + ": '" + echo(name) + "' holds a frame field but no --frames was given");
  check_exposure(exposure);
}

// Stage 3: the clouds' optics (the scene's gas, the flags, the sky's ambient light).
void plan_optics(CloudRenderPlan& p, const CloudRenderArgs& a) {
  render::CloudOptics& optics = p.frame.optics;
  const std::optional<render::Scene>& scene = p.frame.scene;
  optics.extinction_per_m = a.request.optics.extinction_per_m;
  if (!a.settings_given.count(render::Setting::CloudExtinction) && scene && scene->cloud_extinction_per_m)
    optics.extinction_per_m = *scene->cloud_extinction_per_m;  // the scene's gas (steam-lamp: a cup's steam)
  optics.albedo = a.request.optics.albedo;
  optics.phase = a.request.optics.phase;
  // auto: the sky's mean radiance, set with the sun (plan_sun); 0 without a sky.
  if (a.ambient) optics.ambient_radiance = *a.ambient;
  try {
    render::validate(optics);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--cloud-extinction/--cloud-albedo/--ambient: ") + e.what());
  }
}

// Stage 4a: the lamps (--lamp, shaped by --spot), each validated.
void plan_lamps(CloudRenderPlan& p, const CloudRenderArgs& a) {
  const glm::dvec3 intensity = a.lamps.empty() ? glm::dvec3(0.0) : a.lamp_intensity_w_sr;
  // In a scene its bulb shows (a 5 cm sphere, of radiance I / (pi r^2)); clouds never see bulbs. A
  // bulb brighter than the EXR's half floats hold would be clipped in every picture of it.
  const double brightest = std::max({intensity.x, intensity.y, intensity.z});  // W/sr
  const double bulb_radiance = brightest / (kPi * kLampBulbRadiusM * kLampBulbRadiusM);
  if (p.frame.scene && bulb_radiance > kExrHalfMax)
    throw UsageError("--lamp-intensity: " + number_text(brightest) + " W/sr makes each --lamp's bulb, seen in the scene, " +
                     number_text(bulb_radiance) + " W/(m^2 sr), beyond the " + number_text(kExrHalfMax) +
                     " the EXR's half floats hold; at most " +
                     number_text(kExrHalfMax * kPi * kLampBulbRadiusM * kLampBulbRadiusM) +
                     " W/sr with a scene (with --scene none no bulb is drawn)");
  for (const glm::dvec3& at : a.lamps) p.frame.lights.push_back(render::bulb_light(at, intensity, kLampBulbRadiusM));
  refuse_if_given_without(a, "--lamp-intensity", !a.lamps.empty(), "it sets the --lamp lights' intensity, and none was given");
  refuse_if_given_without(a, "--spot-cone", a.spot_axis.has_value(), "it shapes the --spot cone, and no --spot was given");
  for (const char* flag : {"--spp", "--bounces", "--seed"})
    refuse_if_given_without(a, flag, p.cloud_method == render::CloudMethod::PathTrace, "applies to --method pathtrace only");
  if (a.spot_axis) {
    if (a.lamps.empty()) throw UsageError("--spot: it shapes the --lamp lights, and none was given");
    for (render::Light& l : p.frame.lights) {
      l.spot_axis = *a.spot_axis;
      l.spot_inner_rad = a.spot_cone_deg.x * kPi / 180.0;
      l.spot_outer_rad = a.spot_cone_deg.y * kPi / 180.0;
    }
  }
  for (const render::Light& l : p.frame.lights) {
    try {
      render::validate(l);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--lamp/--lamp-intensity/--spot: ") + e.what());
    }
  }
}

// Stage 4b: the sun (--sun, else the scene's, else the default for clouds alone), which a physical
// sky follows; first in the list. True when there is one.
bool plan_sun(CloudRenderPlan& p, const CloudRenderArgs& a) {
  render::Scene* scene = p.frame.scene ? &*p.frame.scene : nullptr;
  std::vector<render::Light>& lights = p.frame.lights;
  std::optional<render::Light> sun;
  std::optional<glm::dvec3> ambient = scene ? render::sky_ambient(*scene) : std::nullopt;
  if (const std::optional<glm::dvec3> to_sun = sun_direction_of(a.sun)) {
    try {
      // The one set-up of the sun (sun_setup.hpp): under the physical sky its colour, the sky
      // behind and the light on the clouds follow it.
      const render::SunSetup setup = render::set_up_sun(scene, *to_sun, render::SunColour::Scene);
      if (scene) render::place_sun(*scene, setup);
      sun = setup.sun;
      ambient = setup.ambient_w_sr_m2;
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--sun: ") + e.what());
    }
  } else if (scene && scene->sun) {
    sun = scene->sun;
  } else if (scene && scene->lamps.empty() && lights.empty()) {
    throw UsageError("--sun: the clouds need the sun or a lamp, and scene '" + scene->name + "' has neither; give --sun X,Y,Z (or --sun-elevation, --time-of-day) or --lamp X,Y,Z");
  } else if (!scene && lights.empty()) {
    sun = render::Light{};  // clouds alone: the default sun
  }
  if (sun) lights.insert(lights.begin(), *sun);
  if (!a.ambient && ambient) p.frame.optics.ambient_radiance = *ambient;
  return sun.has_value();
}

// Stage 5: the renderer's settings: the method, the slicer, the scene's shaft method.
void plan_settings(CloudRenderPlan& p, const CloudRenderArgs& a, bool sun) {
  render::CloudSliceSettings slices = a.request.slices;  // the table's numbers, each checked as its flag was read
  slices.ambient = true;
  slices.multiple = multiple_scattering_of(a, sun);
  // Only the slicer draws a periodic field's copies; the CPU methods draw each cloud once.
  refuse_if_given_without(a, "--repeat-to", p.cloud_method == render::CloudMethod::Slices,
                          "--method " + p.method + " draws each cloud once (the " +
                              (p.cloud_method == render::CloudMethod::PathTrace ? "path tracer" : "reference renderer") +
                              " does not repeat a periodic field); only --method slices draws its copies");
  const bool sky = p.frame.scene && p.frame.scene->name == "sky";
  if (!a.settings_given.count(render::Setting::RepeatTo) && !sky) slices.repeat_to_m = 0.0;  // auto: one tile
  try {
    render::validate(slices);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--slices/--light-res/--multiple/--blur/--max-lights: ") + e.what());
  }
  render::ShaftMethod shafts;
  if (p.frame.scene) {
    shafts = a.request.shafts;
    if (shafts.kind == render::ShaftMethod::Kind::Reference)
      throw UsageError("--shafts: the scene under GPU clouds needs a GPU method, not reference");
  }
  render::FrameSettings& fs = p.frame.settings;
  fs.method = p.cloud_method;
  fs.slices = slices;
  fs.shafts = shafts;
  fs.cloud_shadow_res = a.request.cloud_shadow_res;
  fs.shaft_settings.surface_airlight = a.surface_airlight;
}

// Stage 7: the path tracer's settings, and the one light it traces.
void plan_path_tracer(CloudRenderPlan& p, const CloudRenderArgs& a) {
  render::FrameSettings& fs = p.frame.settings;
  fs.path_tracer.samples_per_pixel = a.spp;
  fs.path_tracer.max_bounces = a.bounces;
  fs.path_tracer.seed = a.seed;
  try {
    render::validate(fs.path_tracer);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--spp/--bounces: ") + e.what());
  }
  if (fs.method == render::CloudMethod::PathTrace &&
      (p.frame.lights.size() != 1 || p.frame.lights[0].kind != render::LightKind::Sun))
    throw UsageError("--lamp: --method pathtrace traces the sun only");
}

// Stage 6: the camera before framing, and the presets to generate.
void plan_camera_and_presets(CloudRenderPlan& p, const CloudRenderArgs& a) {
  render::Camera& camera = p.frame.camera;
  camera = p.frame.scene ? p.frame.scene->camera : render::Camera{};
  if (!p.frame.scene) {
    camera.width = 512;
    camera.height = 512;
    camera.fov_deg = 44.8;  // vdb_render's default
  }
  if (!a.request_file.empty()) {  // its view, as it is (the flags apply over it)
    camera.eye = a.request.camera.eye;
    camera.look_at = a.request.camera.look_at;
    camera.fov_deg = a.request.camera.fov_deg;
  }
  for (const std::string& name : a.presets) {
    try {
      p.presets.push_back(render::load_preset_cloud(name));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--preset: ") + e.what());
    }
  }
}

}  // namespace

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

CloudRenderPlan plan_cloud_render(const CloudRenderArgs& a, const std::string& scene_name, bool scene_given,
                                  const std::string& method_text, bool method_given, const std::string& output,
                                  const std::string& preview, std::optional<double> exposure) {
  CloudRenderPlan p;
  plan_method_and_scene(p, a, scene_name, scene_given, method_text, method_given);
  plan_frames_and_names(p, a, output, preview, exposure);
  plan_optics(p, a);
  plan_lamps(p, a);
  const bool sun = plan_sun(p, a);
  plan_settings(p, a, sun);
  plan_camera_and_presets(p, a);
  plan_path_tracer(p, a);
  return p;
}

}  // namespace nimbus::cli

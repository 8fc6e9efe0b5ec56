// Everything that decides one frame of the animated sky: the sky (clouds, wind, sun), the
// scene, the camera, the two clocks, the cloud optics and the renderer's settings. The viewer
// holds it as its state, saves and loads it (Ctrl+S, Ctrl+O), writes it into every screenshot's
// metadata, and `nimbus render --view-state FILE` renders it offline through the same pipeline.
// The camera, the optics and the slicer's settings are the frame description's own types
// (FrameDescription, render/frame): frame_description(state, quality) copies them in and adds what
// the sky decides (the scene's sun and sky, the ambient light). JSON, its names parsed once as
// it is read; every key is documented in docs/viewer.md.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include <glm/glm.hpp>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_slice_settings.hpp"
#include "nimbus/render/sky/grain_filter.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "nimbus/render/media/shaft_method.hpp"
#include "nimbus/volume/sky.hpp"

namespace nimbus::render {

struct ViewState {
  volume::Sky sky;
  // What lies under and behind the clouds: "sky" (ground, haze and sky lit by the sky's sun),
  // another scene preset (its own lights; its sun, if it has one, follows the sky's), or "none".
  std::string scene = "sky";
  // The view, in the renderer's frame (world_axes.hpp; the file holds it Z-up): eye, look_at and
  // fov_deg are the state's; the window sets the size and the clouds the near and far planes
  // (state_camera, sky_renderer.hpp).
  Camera camera = [] {
    Camera c;
    c.eye = {-600.0, 250.0, 5200.0};
    c.look_at = {400.0, 1500.0, -1500.0};
    c.fov_deg = setting(Setting::Fov).view_default;
    return c;
  }();
  // Clocks: sky time drives the wind's drift; evolution time the keyframes. They run together,
  // except that evolution waits while its keyframes are still being made.
  double sky_time_s = 0.0;
  double evolution_time_s = 0.0;
  double speed = setting(Setting::Speed).view_default;  // sky seconds per real second
  bool paused = false;
  // Cloud optics: extinction, albedo, phase. Their ambient_radiance is not the state's: the
  // sky's daylight sets it as the frame is made (sun_setup.hpp), and it is neither saved nor read.
  CloudOptics optics{setting(Setting::CloudExtinction).view_default, glm::dvec3(kCloudAlbedo), kCloudPhase,
                     glm::dvec3(0.0)};
  // The slicer at full quality (the viewer's adaptive quality lowers slices and scale in
  // motion), jitter (one fixed blue-noise pattern: no flicker), and multiple scattering: the
  // photon-traced light volume (built per keyframe in the background: keyframe_light_volumes.hpp),
  // or octaves (also drawn while the first light volume is being built). A periodic field's tiles
  // are repeated out to repeat_to, within the aerial perspective's 40 km reach. Every number the
  // JSON holds takes its range and its default from the one table (render_settings.hpp), whose
  // view_default is the viewer's where it trades error for speed (2^19 photons, a quarter of
  // `nimbus render`'s: a keyframe's volume in about half a second on 2 cores, 0.4-0.5 points more
  // error, docs/viewer.md). The others keep CloudSliceSettings' defaults.
  CloudSliceSettings slices = [] {
    CloudSliceSettings s;
    s.slices = int(setting(Setting::Slices).view_default);
    s.light_res = int(setting(Setting::LightRes).view_default);
    s.multiple.method = MultipleScatteringMethod::LightVolume;
    s.multiple.octaves = int(setting(Setting::Multiple).view_default);
    s.multiple.light_volume.resolution = int(setting(Setting::MsGrid).view_default);
    s.multiple.light_volume.photons = std::int64_t(setting(Setting::MsPhotons).view_default);
    s.repeat_to_m = setting(Setting::RepeatTo).view_default;
    return s;
  }();
  ShaftMethod shafts = [] {  // a GPU method ("raymarch:24" in the JSON)
    ShaftMethod m;
    m.kind = ShaftMethod::Kind::RayMarch;
    m.steps = 24;
    return m;
  }();
  // A still's grain filter (grain_filter.hpp): on while a still is the mean of few jittered
  // frames ("grain_filter" in the JSON, true or false; the rest of it keeps its defaults).
  GrainFilter grain_filter;
  int cloud_shadow_res = int(setting(Setting::CloudShadowRes).view_default);
  double render_scale = setting(Setting::RenderScale).view_default;  // the frame's share of the window's size
  double exposure_stops = setting(Setting::Exposure).view_default;   // display and PNG screenshots: radiance times 2^stops
};

// Throws std::invalid_argument naming the field.
void validate(const ViewState& state);

// The file format's version. 2: the camera is in nimbus's Z-up world (x east, y north, z up), as
// every flag and file. 1 (a file with no "version"): the camera was Y-up (x east, y up, -z north);
// such files still load, converted. Saving writes version 2.
inline constexpr int kViewStateVersion = 2;

// Throws std::invalid_argument naming `where` and the key; unknown keys are errors.
// `version_read`, when given, receives the file's version (1 when it has none).
ViewState view_state_from_json(const nlohmann::json& doc, const std::string& where, int* version_read = nullptr);
nlohmann::json view_state_to_json(const ViewState& state);

// A state file: std::runtime_error naming the file when unreadable or not JSON,
// std::invalid_argument for bad contents. Saving writes atomically.
ViewState load_view_state(const std::string& path, int* version_read = nullptr);
void save_view_state(const ViewState& state, const std::string& path);

// What a program tells its user about a file read at an old version (empty for the current one):
// that its Y-up camera was converted, and that saving it again writes version 2.
std::string view_state_version_note(const std::string& path, int version);

// The default sky, seen from 250 m up, 5 km south of its nearest clouds.
ViewState default_view_state();

}  // namespace nimbus::render

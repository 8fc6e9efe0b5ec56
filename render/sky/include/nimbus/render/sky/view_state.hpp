// Everything that decides one frame of the animated sky: the sky (clouds, wind, sun), the
// camera, the two clocks, the cloud optics and the renderer's settings. The viewer saves and
// loads it (Ctrl+S, Ctrl+O), writes it into every screenshot's metadata, and
// `nimbus render --view-state FILE` renders it offline through the same pipeline. JSON; every
// key is documented in docs/viewer.md.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include <glm/glm.hpp>

#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/shaft_method.hpp"
#include "nimbus/volume/sky.hpp"

namespace nimbus::render {

struct ViewState {
  volume::Sky sky;
  // What lies under and behind the clouds: "sky" (ground, haze and sky lit by the sky's sun),
  // another scene preset (its own lights; its sun, if it has one, follows the sky's), or "none".
  std::string scene = "sky";
  // Camera (y-up metres, as render::Camera).
  glm::dvec3 eye{-600.0, 250.0, 5200.0};
  glm::dvec3 look_at{400.0, 1500.0, -1500.0};
  double fov_deg = 60.0;
  // Clocks: sky time drives the wind's drift; evolution time the keyframes. They run together,
  // except that evolution waits while its keyframes are still being made.
  double sky_time_s = 0.0;
  double evolution_time_s = 0.0;
  double speed = 10.0;      // sky seconds per real second, [0, 1000]
  bool paused = false;
  // Cloud optics (the ambient comes from the sky: daylight.hpp).
  double extinction_per_m = 0.04;
  glm::dvec3 albedo{0.99};
  DualLobePhase phase{0.7, -0.25, 0.8};
  // Multiple scattering: LightVolume (the photon-traced light volume, built per keyframe in the
  // background: keyframe_light_volumes.hpp) or Octaves (multiple_octaves of them, 0: single
  // scattering; also drawn while the first light volume is being built). Parsed once, where the
  // JSON is read ("light-volume", "octaves").
  MultipleScatteringMethod multiple_method = MultipleScatteringMethod::LightVolume;
  int multiple_octaves = 2;   // [0, 3]
  int ms_grid = 48;                  // light volume cells along the clouds' longest axis, [4, 192]
  // Light volume photons, [1024, 1 << 26]: 2^19, a quarter of `nimbus render`'s, so a keyframe's
  // volume is made in about half a second on 2 cores (docs/viewer.md; 0.4-0.5 points more error).
  std::int64_t ms_photons = 1 << 19;
  // Renderer at full quality (the viewer's adaptive quality lowers slices and scale in motion).
  int slices = 128;           // [8, 1024]
  int light_res = 256;        // [32, 4096]
  ShaftMethod shafts = [] {  // a GPU method ("raymarch:24" in the JSON)
    ShaftMethod m;
    m.kind = ShaftMethod::Kind::RayMarch;
    m.steps = 24;
    return m;
  }();
  int cloud_shadow_res = 256; // [16, 8192]
  double render_scale = 1.0;  // (0, 1]: the frame is rendered at this share of the window's size
  bool jitter = true;         // blue-noise sample offsets within the slabs (one fixed pattern: no flicker)
  double exposure_stops = 0.0;  // display and PNG screenshots: radiance times 2^stops, [-20, 20]
};

// Throws std::invalid_argument naming the field.
void validate(const ViewState& state);

// Throws std::invalid_argument naming `where` and the key; unknown keys are errors.
ViewState view_state_from_json(const nlohmann::json& doc, const std::string& where);
nlohmann::json view_state_to_json(const ViewState& state);

// A state file: std::runtime_error naming the file when unreadable or not JSON,
// std::invalid_argument for bad contents. Saving writes atomically.
ViewState load_view_state(const std::string& path);
void save_view_state(const ViewState& state, const std::string& path);

// The default sky, seen from 250 m up, 5 km south of its nearest clouds.
ViewState default_view_state();

}  // namespace nimbus::render

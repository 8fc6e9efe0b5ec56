// Everything that decides one frame of the animated sky: a render request (render_request.hpp:
// the scene, the camera, the cloud optics and the renderer's settings) plus the sky (clouds,
// wind, sun) and its two clocks. The viewer holds it as its state, saves and loads it (Ctrl+S,
// Ctrl+O), writes it into every screenshot's metadata, and `nimbus render --view-state FILE` renders it offline through the same pipeline.
// The camera, the optics and the slicer's settings are the frame description's own types
// (FrameDescription, render/frame): frame_description(state, quality) copies them in and adds what
// the sky decides (the scene's sun and sky, the ambient light). JSON, its names parsed once as
// it is read; every key is documented in docs/viewer.md.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include <glm/glm.hpp>

#include "nimbus/render/core/render_settings.hpp"
#include "nimbus/render/sky/render_request.hpp"
#include "nimbus/volume/sky.hpp"

namespace nimbus::render {

// The request (render_request.hpp: the scene, the camera, the optics and the renderer's settings)
// plus the sky and its two clocks.
struct ViewState : RenderRequest {
  volume::Sky sky;
  // Clocks: sky time drives the wind's drift; evolution time the keyframes. They run together,
  // except that evolution waits while its keyframes are still being made.
  double sky_time_s = 0.0;
  double evolution_time_s = 0.0;
  double speed = setting(Setting::Speed).view_default;  // sky seconds per real second
  bool paused = false;
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

// One frame's render request as a file holds it: what lies around the clouds, the camera, the
// clouds' optics and the renderer's settings, with one validate and a JSON round trip. The view
// state (view_state.hpp) is this request plus the sky and its clocks, so `nimbus render
// --view-state` and the viewer read the same JSON ("scene", "camera", "optics", "renderer"; every
// key in docs/viewer.md). Its numbers take their ranges from the one table (render_settings.hpp),
// and their defaults from its view defaults, the file format's. frame_description(ViewState)
// (render/frame sky_renderer.hpp) turns it into the FrameDescription the renderer takes.
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_slice_settings.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "nimbus/render/media/shaft_method.hpp"
#include "nimbus/render/sky/grain_filter.hpp"

namespace nimbus::render {

struct RenderRequest {
  // Every number of the one table (render_settings.hpp) at its view default, the file format's:
  // the viewer's where it trades error for speed (2^19 light-volume photons, a quarter of `nimbus
  // render`'s: a keyframe's volume in about half a second on 2 cores, 0.4-0.5 points more error,
  // docs/viewer.md). request_settings.hpp binds each to its field below.
  RenderRequest();

  // What lies under and behind the clouds: "sky" (ground, haze and sky lit by the sky's sun),
  // another scene preset (its own lights; its sun, if it has one, follows the sky's), or "none".
  std::string scene = "sky";
  // The view, in the renderer's frame (world_axes.hpp; the file holds it Z-up): eye, look_at and
  // fov_deg are the request's; the window or the flags set the size and the clouds the near and
  // far planes (state_camera, sky_renderer.hpp).
  Camera camera = [] {
    Camera c;
    c.eye = {-600.0, 250.0, 5200.0};
    c.look_at = {400.0, 1500.0, -1500.0};
    return c;
  }();
  // Cloud optics: extinction (the table's), albedo, phase. Their ambient_radiance is not the
  // request's: the sky's daylight sets it as the frame is made (sun_setup.hpp), and it is neither
  // saved nor read.
  CloudOptics optics{0.0, glm::dvec3(kCloudAlbedo), kCloudPhase, glm::dvec3(0.0)};
  // The slicer at full quality (the viewer's adaptive quality lowers slices and scale in
  // motion), jitter (one fixed blue-noise pattern: no flicker), and multiple scattering: the
  // photon-traced light volume (built per keyframe in the background: keyframe_light_volumes.hpp),
  // or octaves (also drawn while the first light volume is being built). A periodic field's tiles
  // are repeated out to repeat_to, within the aerial perspective's 40 km reach.
  CloudSliceSettings slices = [] {
    CloudSliceSettings s;
    s.multiple.method = MultipleScatteringMethod::LightVolume;
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
  int cloud_shadow_res = 0;   // texels per side of the clouds' shadow on the scene
  double render_scale = 1.0;  // the frame's share of the window's size
  double exposure_stops = 0.0;  // display and PNG screenshots: radiance times 2^stops
};

// Throws std::invalid_argument naming the field as `what` KEY ("view state optics: ...").
void validate(const RenderRequest& request, const std::string& what = "render request");

// Reads the request's key `k` ("scene", "camera", "optics" or "renderer") of a file whose camera is
// of `camera_version` (2: Z-up; 1: the renderer's own Y-up frame) into `request`; false for any
// other key. Throws std::invalid_argument naming `key` for a bad value or an unknown member.
bool read_render_request_key(RenderRequest& request, const std::string& k, const nlohmann::json& value,
                             const std::string& key, int camera_version);

// The request alone (no sky, no clocks): unknown keys are errors, and the result is validated.
RenderRequest render_request_from_json(const nlohmann::json& doc, const std::string& where);
// {"scene", "camera", "optics", "renderer"}: what render_request_from_json reads back to the same
// request.
nlohmann::json render_request_to_json(const RenderRequest& request);

}  // namespace nimbus::render

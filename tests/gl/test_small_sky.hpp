// The GL suites' small sky: a cumulus humilis and a mediocris at 60 m voxels, keyframes every
// 10 s of sky time, the sun at 35 degrees, seen from 4 km by the camera small_sky_camera puts in
// a state. Quick to generate and draw; each suite sets its own wind, evolution and renderer.
#pragma once
#include <nlohmann/json.hpp>

#include "nimbus/render/sky/view_state.hpp"

namespace nimbus::test {

// The sky file's JSON with this wind (metres per second) and evolution rate.
inline nlohmann::json small_sky_json(double wind_x, double wind_y, double evolution) {
  return {{"clouds",
           {{{"preset", "cumulus-humilis"}, {"position", {-400, 0, 0}}, {"seed", 1}},
            {{"preset", "cumulus-mediocris"}, {"position", {900, 600, 0}}, {"seed", 2}}}},
          {"wind", {wind_x, wind_y, 0}},
          {"evolution", evolution},
          {"sun", {{"elevation", 35}, {"azimuth", 135}}},
          {"voxel_size", 60},
          {"keyframe_interval", 10}};
}

// A view state's camera that has both clouds in view.
inline nlohmann::json small_sky_camera() {
  return {{"eye", {-300, 300, 4200}}, {"look_at", {300, 1400, 0}}, {"fov", 60}};
}

// The two clouds, still (no wind, time paused), over the sky scene (sky, ground, shafts), with
// the octaves for multiple scattering: a view whose pixels the progressive and temporal frames
// are tested on (the light volume is not what they test).
inline render::ViewState small_sky_still_state() {
  render::ViewState s =
      render::view_state_from_json({{"sky", small_sky_json(0.0, 0.0, 1.0)}, {"camera", small_sky_camera()}}, "test state");
  s.scene = "sky";
  s.paused = true;
  s.slices.multiple.method = render::MultipleScatteringMethod::Octaves;
  return s;
}

}  // namespace nimbus::test

// One frame, described once: the scene and its lights, the lights on clouds alone, the clouds'
// optics, the camera and the renderer's settings. `nimbus render` builds it from its flags
// (samples/cli/render_clouds_plan.cpp), the viewer from its state (frame_description(ViewState),
// sky_renderer.hpp), and FrameRenderer takes it; the clouds themselves arrive frame by frame
// (set_clouds: a frame's files or presets, or a keyframe pair of the sky).
#pragma once
#include <optional>
#include <vector>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/light.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/frame/frame_settings.hpp"

namespace nimbus::render {

struct FrameDescription {
  // What lies behind and around the clouds, with its own lights (its sun and lamps light the
  // clouds too), or none: the clouds alone over transparent black.
  std::optional<Scene> scene;
  // Lights beyond the scene's: a sun here replaces the scene's, a lamp joins its lamps; without a
  // scene, every light on the clouds (light.hpp).
  std::vector<Light> lights;
  CloudOptics optics;    // every cloud's (its ambient: the sky's light, sun_setup.hpp)
  Camera camera;         // the view; a program may reframe it per frame (FrameRenderer::render takes one)
  FrameSettings settings;
};

}  // namespace nimbus::render

// The frame pipeline: clouds over a scene, one frame at a time. For the half-angle slicer it
// builds the clouds' shadow map, draws the scene's surfaces and light shafts under that shadow
// (shafts/), slices the clouds over them (clouds/) and writes the frame's metadata; for the CPU
// reference it renders the clouds alone. `nimbus render` and the viewer draw through it, so a
// frame is the same whichever program asks for it.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "nimbus/render/clouds/cloud_renderer.hpp"
#include "nimbus/render/core/cloud_slice_settings.hpp"
#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_method.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/media/shaft_method.hpp"
#include "nimbus/render/frame/frame_description.hpp"
#include "nimbus/render/frame/frame_settings.hpp"
#include "nimbus/render/scene/sun_setup.hpp"
#include "nimbus/render/reference/cloud_path_tracer.hpp"
#include "nimbus/render/reference/cloud_reference.hpp"
#include "nimbus/render/shafts/shaft_renderer.hpp"

namespace nimbus::render {

class CloudShadowBuilder;

// What a frame cost, pass by pass.
struct FrameStats {
  ShaftFrameStats scene;    // the surfaces and shafts under the clouds (zeros without a scene)
  CloudFrameStats clouds;   // the slicer's passes (zeros for the reference)
  // The light volume's build on the CPU this frame (multiple-scattering method light-volume),
  // apart from the GPU passes: 0 when the last one was reused.
  double light_volume_build_ms = 0;
  bool light_volume_rebuilt = false;  // this frame built a new light volume
  std::string device;       // GL_RENDERER, or "CPU (double precision)"
  std::string summary;      // one line of the times above; empty for the reference
};

class FrameRenderer {
 public:
  // The frame described once (frame_description.hpp): its scene and lights as below, its settings,
  // and its optics on every cloud set (set_clouds, set_optics). The camera is render()'s to take.
  explicit FrameRenderer(const FrameDescription& frame);
  // `scene`: what lies behind and around the clouds (its sun is set to `light`, and gets one if
  // it had none), or nullopt: the clouds alone over transparent black. The Reference method takes
  // no scene. The Slices method draws into the GL 4.5 context current on the calling thread.
  // Throws std::invalid_argument naming a bad scene, light or setting.
  FrameRenderer(std::optional<Scene> scene, const Light& light, const FrameSettings& settings);
  // Any lights (light.hpp): at most one sun (the scene's sun, as above; else the scene's own
  // sun, if it has one, lights the clouds) and lamps. With a scene, a lamp (or spot) joins its
  // lamps, and every lamp of the scene lights the clouds too; without one, the lamps light the clouds alone. Throws
  // std::invalid_argument when nothing lights the clouds, for two suns, or for lamps with the path
  // tracer (sun only).
  FrameRenderer(std::optional<Scene> scene, std::vector<Light> lights, const FrameSettings& settings);
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  // The clouds of the next frames (uploaded for Slices; the programs stay compiled), each drawn
  // with the frame's optics when it was made from a FrameDescription. Throws
  // std::invalid_argument for an empty list or a bad cloud, keeping the old clouds.
  void set_clouds(std::vector<CloudVolume> clouds);
  // The clouds as drawn (moved).
  const std::vector<CloudVolume>& clouds() const;

  // Moves the clouds from where set_clouds put them (wind drift, keyframe blend; one entry per
  // cloud), with no upload. Throws std::invalid_argument for a wrong count or a bad motion.
  void set_motion(const std::vector<CloudMotion>& motion);

  // The same optics for every cloud, with no upload (std::invalid_argument for bad optics).
  void set_optics(const CloudOptics& optics);

  // New settings for the next frames (the viewer's adaptive quality). The method and the volume
  // format cannot change (std::invalid_argument); new shaft settings rebuild the scene's renderer.
  void set_settings(const FrameSettings& settings);

  // A light volume made elsewhere (the animated sky builds one per keyframe in the background,
  // sky_renderer.hpp): from now on the Slices method draws it, as given, and builds none of its
  // own; move_light_volume shifts its corner with no upload (the wind's drift). Throws
  // std::logic_error for a method other than Slices or before set_clouds, and std::invalid_argument
  // for a bad volume (CloudRenderer::set_light_volume).
  void set_light_volume(const LightVolume& volume);
  void move_light_volume(const glm::dvec3& world_min);
  bool has_light_volume() const;

  // Moves the sun (the scene's too; adds one if there was none): its shadow maps (and a light
  // volume, if the direction changed) are rebuilt at the next frame. std::invalid_argument for a lamp.
  void set_light(const Light& light);
  // A new sky behind the scene (its gradient follows the sun in the viewer).
  void set_sky(const Sky& sky);
  // The sun as set up by set_up_sun (sun_setup.hpp): set_light(setup.sun), and set_sky with its
  // physical sky when it brings one and there is a scene. Its ambient light is the caller's to put
  // in the optics (set_optics).
  void set_sun(const SunSetup& setup);
  // The sun, held once: in the scene when there is one, else here. light() is it (the default
  // sun when there is none).
  const std::optional<Light>& sun() const { return scene_ ? scene_->sun : sun_; }
  bool has_sun() const { return sun().has_value(); }
  Light light() const;
  // Every light on the clouds: the sun, then the lamps (the scene's, or those given without a
  // scene), as they are: one light model from the scene to the clouds.
  std::vector<Light> cloud_lights() const;
  const std::optional<Scene>& scene() const { return scene_; }
  const FrameSettings& settings() const { return settings_; }

  // One frame through `camera` (validated). With `stats`, every pass is timed (on llvmpipe that
  // waits for each pass to finish); without, nothing waits. Metadata: the scene's (describe_frame, method
  // "slices over <shafts>"), the clouds', the slicer's or the reference's settings, and "device".
  // Throws std::logic_error when no clouds were set, std::runtime_error when a pixel came out
  // NaN or infinite. `depths`: what each pixel shows and how far (pixel_depths.hpp), for the
  // Slices method over a scene; otherwise left empty.
  Image render(const Camera& camera, FrameStats* stats = nullptr, PixelDepths* depths = nullptr);

 private:
  std::optional<Scene> scene_;
  std::optional<Light> sun_;    // the sun without a scene (with one, scene_->sun)
  std::vector<Light> lamps_;  // lamps on clouds without a scene
  std::optional<CloudOptics> optics_;  // the frame's optics on every cloud (FrameDescription), else each cloud's own
  FrameSettings settings_;
  std::vector<CloudVolume> reference_clouds_;  // Reference: the clouds as set (Slices keeps them in cloud_renderer_)
  std::vector<CloudVolume> reference_moved_;   // Reference: the same, moved by set_motion
  std::unique_ptr<CloudRenderer> cloud_renderer_;
  std::unique_ptr<ShaftRenderer> shaft_renderer_;
  std::unique_ptr<CloudShadowBuilder> shadow_builder_;
  // The light volume is rebuilt when the clouds, their motion or optics, the light's direction or
  // the light-volume settings change, and only then.
  bool light_volume_stale_ = true;
  bool light_volume_given_ = false;  // set_light_volume: never build one here
  LightVolumeSettings light_volume_built_;
  std::string light_volume_description_;
  double update_light_volume();  // ms spent building, 0 if reused
};

}  // namespace nimbus::render

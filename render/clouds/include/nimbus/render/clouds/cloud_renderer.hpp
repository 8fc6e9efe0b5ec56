// The half-angle slice renderer (Kniss et al. 2002/2003; Hoffmann 2007, "Wolken-Renderer mit
// OpenGL"): slice planes perpendicular to the half vector of the view direction and the light's
// propagation direction, drawn in light order; each slice is shaded from the light buffer, then
// attenuates it, so the clouds shadow themselves. Optionally composited over an opaque scene
// with fog in front. Draws into the current GL 4.5 context.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/core/pixel_depths.hpp"
#include "nimbus/render/core/light_volume.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/core/cloud_slice_settings.hpp"
#include "nimbus/render/gl/volume_texture.hpp"

namespace nimbus::render {


struct CloudFrameStats {
  double light_ms = 0, slices_ms = 0, composite_ms = 0, total_ms = 0;  // GPU time per pass
  // Fragment shader invocations per pass (GpuTimer::fragments); -1 where the driver does not count.
  double light_fragments = -1, slices_fragments = -1, composite_fragments = -1;
  int slices_drawn = 0;           // over every light's pass
  int light_passes = 0;           // lights drawn (one slicing pass each)
  bool front_to_back = false;    // the eye composites under (light behind the viewer)
  double half_angle_rad = 0;     // between the slicing axis and the view direction (first light)
  std::string timing;            // how the times were taken
};

// What lies behind and around the clouds: the opaque scene as ShaftRenderer drew it.
struct SceneUnderlay {
  GLuint color_texture = 0;     // RGBA32F, camera-sized: the scene's premultiplied radiance (shafts included)
  GLuint distance_texture = 0;  // R32F, camera-sized: metres along each pixel's ray to the surface, 0 = none
  const Scene* scene = nullptr; // its medium attenuates the clouds and adds unshadowed airlight in front of them
};

class CloudRenderer {
 public:
  // Uploads every cloud (volume_texture.hpp; GL_R16F or GL_R32F). Throws std::invalid_argument
  // for an empty list or a bad cloud (naming it). Needs a current GL 4.5 context.
  explicit CloudRenderer(std::vector<CloudVolume> clouds, GLenum format = GL_R16F);
  ~CloudRenderer();
  CloudRenderer(const CloudRenderer&) = delete;
  CloudRenderer& operator=(const CloudRenderer&) = delete;

  // Replaces the clouds (a sequence's next frame), keeping the compiled programs. Same errors
  // as the constructor; on an error the old clouds stay.
  void set_clouds(std::vector<CloudVolume> clouds, GLenum format = GL_R16F);

  // Moves each cloud from where set_clouds put it (one entry per cloud, in order): the wind's
  // drift and the keyframe blend, with no upload. Throws std::invalid_argument for a wrong
  // count or a bad motion, keeping the old one.
  void set_motion(const std::vector<CloudMotion>& motion);

  // The same optics for every cloud from the next frame on (no upload). Throws
  // std::invalid_argument for bad optics.
  void set_optics(const CloudOptics& optics);

  // The light volume that the multiple-scattering method light-volume reads (light_volume.hpp;
  // built on the CPU by render/reference light_volume_builder.hpp, by FrameRenderer when the light
  // or the clouds change). Uploaded as given; kept until replaced. Throws std::invalid_argument
  // when its sizes and values do not agree or a value is not finite.
  void set_light_volume(const LightVolume& volume);
  bool has_light_volume() const;
  // Moves the uploaded light volume's corner (world metres), with no upload: the clouds' wind
  // drift carries their scattered light along. Throws std::logic_error before set_light_volume and
  // std::invalid_argument for a non-finite corner.
  void move_light_volume(const glm::dvec3& world_min);

  // The clouds as they are drawn (moved).
  const std::vector<CloudVolume>& clouds() const;
  std::vector<const VolumeTexture*> textures() const;  // in the clouds' order (cloud_shadow.hpp)
  std::vector<const VolumeTexture*> next_textures() const;  // their next keyframes (nullptr: none)

  // One frame (std::logic_error for the light-volume method before set_light_volume). Without an underlay: clouds over transparent black, RGB premultiplied radiance,
  // alpha = 1 - transmittance (comparable with render_cloud_reference). With one: slices behind
  // the scene's surfaces are hidden, fog in front of the clouds attenuates them and adds its
  // airlight, and the result is the finished frame. Metadata: describe_clouds' and describe_slices'.
  Image render(const Camera& camera, const Light& light, const CloudSliceSettings& settings,
               const SceneUnderlay* underlay = nullptr, CloudFrameStats* stats = nullptr);
  // Several lights (the sun, lamps, spots; light.hpp): the settings.max_lights strongest at
  // the clouds' centre get one slicing pass each, with its own axis and light buffer (a lamp's is
  // its perspective view); their radiance adds up, the coverage is the first pass's, the ambient
  // term enters once. Lights left out are named in the metadata key "lights_left_out". A lamp
  // takes the octaves method of multiple scattering (std::invalid_argument with light-volume).
  // `depths`: with an underlay, what each pixel shows and how far (pixel_depths.hpp), read back
  // from the composite; without one it is left empty. With settings.repeat_to_m > 0, periodic
  // clouds (CloudVolume::period_m) are drawn with copies of their tiles (cloud_tiles.hpp): the
  // lights' passes draw the near ones, and one more pass, lit by the first light, draws the far
  // copies under them (metadata key "periodic_copies").
  Image render(const Camera& camera, const std::vector<Light>& lights, const CloudSliceSettings& settings,
               const SceneUnderlay* underlay = nullptr, CloudFrameStats* stats = nullptr,
               PixelDepths* depths = nullptr);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nimbus::render

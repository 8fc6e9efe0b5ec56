// The GPU light-shaft renderer: the scene's surfaces lit with shadow maps and attenuated by the
// medium, plus the single-scattered airlight of each light by ray marching, the analytic
// airlight or shadow-volume intervals (shaft_method.hpp). Draws into the current GL 4.5 context.
#pragma once
#include <cstddef>
#include <memory>
#include <string>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/gl/cloud_shadow_map.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/media/shaft_method.hpp"
#include "nimbus/render/core/shaft_settings.hpp"

namespace nimbus::render {

// Per-frame costs (GPU time per pass, ms) and what the shadow-volume pass built.
struct ShaftFrameStats {
  double shadow_maps_ms = 0, surfaces_ms = 0, shadow_volume_ms = 0, shafts_ms = 0, total_ms = 0;
  // Fragment shader invocations per pass (GpuTimer::fragments); -1 where the driver does not count.
  double shadow_maps_fragments = -1, surfaces_fragments = -1, shadow_volume_fragments = -1, shafts_fragments = -1;
  std::size_t skirt_quads = 0;   // summed over lights
  bool skirt_overflow = false;   // a light's skirts exceeded max_skirt_quads
  std::string timing;            // how the times were taken
};

class ShaftRenderer {
 public:
  // Validates the scene (std::invalid_argument) and uploads its geometry. Needs a current GL
  // 4.5 context; at most 4 point lights and one sun.
  ShaftRenderer(const Scene& scene, const ShaftSettings& settings = {});
  ~ShaftRenderer();
  ShaftRenderer(const ShaftRenderer&) = delete;
  ShaftRenderer& operator=(const ShaftRenderer&) = delete;

  // One frame. `method` must not be Reference (that is render_reference, on the CPU); the
  // analytic table form covers the isotropic phase only (std::invalid_argument otherwise).
  Image render(const Camera& camera, const ShaftMethod& method, ShaftFrameStats* stats = nullptr);
  // Varies the ray march's jitter from frame to frame (CloudSliceSettings::frame): frame f adds
  // f times the golden ratio, modulo 1, to every pixel's jitter value; 0 keeps the tile's.
  void set_jitter_frame(unsigned frame);

  // The clouds' shadow (gl/cloud_shadow_map.hpp), multiplied into the sun's visibility on surfaces in
  // every method and in the fog's shafts by ray marching (the analytic and shadow-volume
  // methods' closed forms assume no cloud). The map must outlive its use; null removes it.
  void set_cloud_shadow(const CloudShadowMap* map);

  // The last frame's GL textures, valid until the next render (cloud_renderer.hpp's underlay):
  // RGBA32F premultiplied radiance, and R32F distance to the surface (metres, 0 = none).
  GLuint color_texture() const;
  GLuint distance_texture() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nimbus::render

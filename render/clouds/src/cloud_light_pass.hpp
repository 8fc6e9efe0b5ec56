// One light's pass of the half-angle slice renderer (Kniss et al. 2003): its plan on the CPU (the
// slicing axis, the planes, the polygons and the light buffer's frame) and its draw on the GPU (the
// pass's uniforms, every cloud's block, and the slice loop that alternates an eye draw and a light
// draw). A second light's pass on draws into the pass buffer and is added into the eye buffer.
// Private to render/clouds/src/cloud_*.cpp.
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cloud_renderer_impl.hpp"
#include "cloud_slice_geometry.hpp"
#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/light.hpp"

namespace nimbus::render::cloud_detail {

// What a light's pass draws, planned on the CPU.
struct LightPassPlan {
  bool lamp = false;                // a point light or spot: a perspective light buffer
  glm::dvec3 l{0.0, -1.0, 0.0};     // unit propagation direction (a lamp's at the clouds' centre)
  SliceAxis axis;
  SlicePlanes planes;
  SliceMesh mesh;                   // every (slice, cloud) polygon
  double light_slab_m = 0.0;        // a slab's thickness along the light (spacing / dot(l, s))
  LightFrame light_frame;           // the sun's orthographic light buffer
  LampFrame lamp_frame;             // a lamp's perspective one
  glm::dvec2 texel_m{1.0};          // a light-buffer texel at the clouds' centre, metres
  std::string note;                 // for a lamp: slices on its near side, clipping (metadata)
};

// The pass of light number `pass` (0: the first, which also carries the ambient term).
LightPassPlan plan_light_pass(const CloudRenderer::Impl& s, const Camera& camera, const Light& light,
                              const glm::dvec3& centre, const CloudSliceSettings& settings, int pass);

// What every pass of a frame shares.
struct FrameContext {
  const Camera& camera;
  const CameraBlock& camera_block;
  const CloudSliceSettings& settings;
  bool light_volume = false;              // the multiple-scattering method reads the light volume
  bool light_radiance = false;            // ...from the radiance made toward this eye (MS_VOLUME 2)
  const SceneUnderlay* underlay = nullptr;
  GpuTimer& timer;
};

// Draws the planned pass (into the eye buffer for pass 0, else into the pass buffer, then added
// into the eye buffer's radiance). Returns how many slices it drew.
int draw_light_pass(CloudRenderer::Impl& s, const FrameContext& frame, const Light& light,
                    const LightPassPlan& plan, int pass);

}  // namespace nimbus::render::cloud_detail

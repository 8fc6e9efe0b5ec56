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
#include "nimbus/render/core/cloud_tiles.hpp"
#include "nimbus/render/core/light.hpp"

namespace nimbus::render::cloud_detail {

// The clouds one slicing draws: copies of the renderer's clouds (cloud_tiles.hpp), each with its
// hull moved by its offset.
struct PassClouds {
  std::vector<CloudInstance> instances;
  std::vector<ConvexHull> hulls;        // each instance's
  std::vector<glm::dvec3> hull_points;  // all their vertices
  bool moved = false;                   // a copy lies off its cloud (an offset is not 0)
  bool far = false;                     // the far copies' pass (tile_slices)
  // With copies (moved): each one's radiance toward the eye, -1 the clouds' own
  // (light_radiance_tex), else copy_radiance_tex[k]; empty: none made, the pass reads the light
  // volume per sample.
  std::vector<int> radiance;
};
PassClouds pass_clouds(const CloudRenderer::Impl& s, std::vector<CloudInstance> instances);

// Where a pass's slices go: the eye buffer (the first light's near pass), added into it (a later
// light's), or under it (the far copies, behind everything the near passes drew).
enum class PassTarget { Eye, AddToEye, UnderEye };

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

// The pass of light number `pass` over the clouds `pc` (the lamp notes name the pass).
LightPassPlan plan_light_pass(const CloudRenderer::Impl& s, const PassClouds& pc, const Camera& camera, const Light& light,
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

// Draws the planned pass of the clouds `pc` to `target` (AddToEye and UnderEye draw into the pass
// buffer first). The ambient term enters with the passes to Eye and UnderEye, once per pixel's
// clouds. Returns how many slices it drew.
int draw_light_pass(CloudRenderer::Impl& s, const PassClouds& pc, const FrameContext& frame, const Light& light,
                    const LightPassPlan& plan, PassTarget target);

}  // namespace nimbus::render::cloud_detail

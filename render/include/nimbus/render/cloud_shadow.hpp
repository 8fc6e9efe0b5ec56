// The clouds' shadow in the scene: the optical depth through every cloud along the sun's
// direction, on an orthographic map over the clouds' footprint, with the range of depths where
// the cloud matter lies. The ground and the fog's light shafts take its transmittance as
// visibility next to the opaque shadow map (shaders/lib/cloud_shadow.glsl). View-independent,
// so built once per light and set of clouds.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/cloud_optics.hpp"
#include "nimbus/render/cloud_volume.hpp"
#include "nimbus/render/gl_resources.hpp"
#include "nimbus/render/shader_program.hpp"
#include "nimbus/render/volume_texture.hpp"

namespace nimbus::render {

struct CloudShadowMap {
  GlTexture optical_depth;  // R32F: tau along the light through all clouds (linear filtering)
  GlTexture depth_range;    // RG32F: nearest and farthest depth along the light (metres) with matter
  int resolution = 0;
  // World -> map: x, y in [0, 1] across the footprint, z = depth in metres along the light's
  // propagation direction from the map's plane (which lies on the light's side of every cloud).
  glm::dmat4 world_to_map{1.0};
  double top_y_m = -1e300;  // highest point of the clouds' support (world y): no cloud shadow above it
};

// Marches each texel's light ray through the clouds (half-voxel steps). Points between the
// nearest and farthest depth see tau scaled linearly between them; before, none; beyond, all.
// Needs a current GL 4.5 context; `textures` are the clouds uploaded in the same order.
// The same with the compute program compiled once (a sequence builds one map per frame).
class CloudShadowBuilder {
 public:
  CloudShadowBuilder();  // compiles; needs a current GL 4.5 context
  CloudShadowMap build(const std::vector<CloudVolume>& clouds, const std::vector<const VolumeTexture*>& textures,
                       const CloudLight& light, int resolution = 512) const;

 private:
  ShaderProgram program_;
};

CloudShadowMap build_cloud_shadow_map(const std::vector<CloudVolume>& clouds,
                                      const std::vector<const VolumeTexture*>& textures, const CloudLight& light,
                                      int resolution = 512);

// Binds `map` for shaders that include lib/cloud_shadow.glsl, on texture units `unit` and
// `unit + 1` of `program`; a null map binds "no clouds" (transmittance 1 everywhere).
void bind_cloud_shadow(GLuint program, const CloudShadowMap* map, int unit);

}  // namespace nimbus::render

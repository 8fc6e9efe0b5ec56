// The clouds' shadow in the scene, as the GPU holds it: the optical depth through every cloud
// along the sun's direction on an orthographic map over the clouds' footprint, with the range of
// depths where the cloud matter lies. The clouds layer builds it (clouds/cloud_shadow.hpp); the
// ground and the fog's light shafts take its transmittance as visibility next to the opaque
// shadow map (shaders/lib/cloud_shadow.glsl). Here, between the two, so neither depends on the
// other.
#pragma once
#include <glm/glm.hpp>

#include "nimbus/render/media/atmosphere.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/shader_program.hpp"

namespace nimbus::render {

struct CloudShadowMap {
  GlTexture optical_depth;  // R32F: tau along the light through all clouds (linear filtering)
  GlTexture depth_range;    // RG32F: nearest and farthest depth along the light (metres) with matter
  int resolution = 0;
  // World -> map: x, y in [0, 1] across the footprint, z = depth in metres along the light's
  // propagation direction from the map's plane (which lies on the light's side of every cloud).
  glm::dmat4 world_to_map{1.0};
  double top_y_m = -1e300;  // highest point of the clouds' support (world y): no cloud shadow above it
  // The sun's angular radius: the penumbra on surfaces is the distance to the occluding matter
  // times its tangent (lib/cloud_shadow.glsl, cloud_transmittance_soft). The physical sky's sun.
  double sun_angular_radius_rad = Atmosphere{}.sun_angular_radius_rad;
};

// Binds `map` for a program built with lib/cloud_shadow.glsl and CLOUD_SHADOW 1 (its matrix, and
// its textures on UNIT_CLOUD_TAU and UNIT_CLOUD_RANGE). A null map binds nothing: programs built
// with CLOUD_SHADOW 0 see no clouds (transmittance 1 everywhere).
void bind_cloud_shadow(const ShaderProgram& program, const CloudShadowMap* map);

}  // namespace nimbus::render

// Binding the clouds' shadow map for lib/cloud_shadow.glsl (cloud_shadow_map.hpp).
#include "nimbus/render/gl/cloud_shadow_map.hpp"

#include "nimbus/render/core/shader_contract.hpp"

namespace nimbus::render {

void bind_cloud_shadow(const ShaderProgram& program, const CloudShadowMap* map) {
  if (map == nullptr) return;  // programs built with CLOUD_SHADOW 0 declare none of it
  program.set("u_world_to_cloud_map", glm::mat4(map->world_to_map));
  program.set("u_sun_angular_radius", static_cast<float>(map->sun_angular_radius_rad));
  glBindTextureUnit(contract::UNIT_CLOUD_TAU, map->optical_depth.id());
  glBindTextureUnit(contract::UNIT_CLOUD_RANGE, map->depth_range.id());
}

}  // namespace nimbus::render

// Binding the clouds' shadow map for lib/cloud_shadow.glsl (cloud_shadow_map.hpp).
#include "nimbus/render/gl/cloud_shadow_map.hpp"

namespace nimbus::render {

void bind_cloud_shadow(GLuint program, const CloudShadowMap* map, int unit) {
  auto set_int = [&](const char* name, int value) {
    if (GLint loc = glGetUniformLocation(program, name); loc >= 0) glProgramUniform1i(program, loc, value);
  };
  set_int("u_has_cloud_shadow", map ? 1 : 0);
  set_int("u_cloud_tau", unit);
  set_int("u_cloud_range", unit + 1);
  if (!map) return;
  if (GLint loc = glGetUniformLocation(program, "u_world_to_cloud_map"); loc >= 0) {
    const glm::mat4 m(map->world_to_map);
    glProgramUniformMatrix4fv(program, loc, 1, GL_FALSE, &m[0][0]);
  }
  glBindTextureUnit(static_cast<GLuint>(unit), map->optical_depth.id());
  glBindTextureUnit(static_cast<GLuint>(unit + 1), map->depth_range.id());
}

}  // namespace nimbus::render

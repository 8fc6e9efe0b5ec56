// Uploading and binding the physical sky's tables (atmosphere_textures.hpp).
#include "nimbus/render/gl/atmosphere_textures.hpp"

#include <epoxy/gl.h>

#include <stdexcept>

#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/gl/to_float.hpp"

namespace nimbus::render {
namespace {

// 2D tables are read with texelFetch (exact bilinear weights), 3D ones with the linear filter.
GlTexture upload(const AtmosphereTable& t) {
  TextureParams p;
  p.min_filter = t.depth > 1 ? GL_LINEAR : GL_NEAREST;
  p.mag_filter = p.min_filter;
  if (t.depth > 1) {
    GlTexture tex = make_texture_3d(GL_RGB32F, t.width, t.height, t.depth, p);
    glTextureSubImage3D(tex.id(), 0, 0, 0, 0, t.width, t.height, t.depth, GL_RGB, GL_FLOAT, t.texels.data());
    return tex;
  }
  GlTexture tex = make_texture_2d(GL_RGB32F, t.width, t.height, p);
  glTextureSubImage2D(tex.id(), 0, 0, 0, t.width, t.height, GL_RGB, GL_FLOAT, t.texels.data());
  return tex;
}

}  // namespace

AtmosphereTextures upload_atmosphere(std::shared_ptr<const AtmosphereTables> tables) {
  if (!tables) throw std::invalid_argument("atmosphere textures: no tables");
  AtmosphereTextures t;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  t.sky_view = upload(tables->sky_view);
  t.aerial_scattering = upload(tables->aerial_scattering);
  t.aerial_transmittance = upload(tables->aerial_transmittance);
  t.tables = std::move(tables);
  return t;
}

void bind_sky_view(const ShaderProgram& p, const AtmosphereTextures& t) {
  p.set("u_sky_physical", 1);
  p.set("u_sky_sun", to_float(t.tables->view.direction_to_sun));
  p.set("u_sky_cos_horizon", static_cast<float>(horizon_cos(t.tables->atmosphere, t.tables->view.altitude_m)));
  glBindTextureUnit(contract::UNIT_SKY_VIEW, t.sky_view.id());
}

void bind_aerial_perspective(const ShaderProgram& p, const AtmosphereTextures& t) {
  p.set("u_aerial_on", 1);
  p.set("u_aerial_sun", to_float(t.tables->view.direction_to_sun));
  p.set("u_aerial_cos_horizon", static_cast<float>(horizon_cos(t.tables->atmosphere, t.tables->view.altitude_m)));
  p.set("u_aerial_max_distance_m", static_cast<float>(t.tables->view.aerial_max_distance_m));
  glBindTextureUnit(contract::UNIT_AERIAL_SCATTERING, t.aerial_scattering.id());
  glBindTextureUnit(contract::UNIT_AERIAL_TRANSMITTANCE, t.aerial_transmittance.id());
}

}  // namespace nimbus::render

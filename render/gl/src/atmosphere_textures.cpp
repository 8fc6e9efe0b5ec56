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

SkyBlock sky_block(const Sky* sky, const AtmosphereTextures* tables) {
  SkyBlock b;
  if (sky) {
    b.has_sky = 1;
    b.zenith = to_float(sky->zenith_radiance_w_sr_m2);
    b.horizon = to_float(sky->horizon_radiance_w_sr_m2);
    b.distance_m = static_cast<float>(sky->distance_m);
  }
  if (tables) {
    const AtmosphereTables& t = *tables->tables;
    b.physical = 1;
    b.aerial_on = 1;
    b.sun = to_float(t.view.direction_to_sun);
    b.cos_horizon = static_cast<float>(horizon_cos(t.atmosphere, t.view.altitude_m));
    b.aerial_max_distance_m = static_cast<float>(t.view.aerial_max_distance_m);
  }
  return b;
}

void bind_atmosphere_textures(const AtmosphereTextures& t) {
  glBindTextureUnit(contract::UNIT_SKY_VIEW, t.sky_view.id());
  glBindTextureUnit(contract::UNIT_AERIAL_SCATTERING, t.aerial_scattering.id());
  glBindTextureUnit(contract::UNIT_AERIAL_TRANSMITTANCE, t.aerial_transmittance.id());
}

}  // namespace nimbus::render

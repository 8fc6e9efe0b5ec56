// The physical sky's tables (render/media/atmosphere_tables.hpp) as textures: the sky view for
// the sky behind the scene (shaders/lib/sky.glsl), the aerial perspective for the haze in front
// of the clouds (shaders/lib/aerial_perspective.glsl). RGB32F, read with texelFetch and the
// tables' own bilinear weights, so the GPU reads what the CPU reads.
#pragma once
#include <memory>

#include "nimbus/render/media/atmosphere_tables.hpp"
#include "nimbus/render/gl/resources.hpp"

namespace nimbus::render {

class ShaderProgram;

struct AtmosphereTextures {
  std::shared_ptr<const AtmosphereTables> tables;
  GlTexture sky_view, aerial_scattering, aerial_transmittance;
};

// Uploads the tables (a current GL context is needed).
AtmosphereTextures upload_atmosphere(std::shared_ptr<const AtmosphereTables> tables);

// Sets lib/sky.glsl's physical-sky uniforms and binds the sky view to UNIT_SKY_VIEW.
void bind_sky_view(const ShaderProgram& p, const AtmosphereTextures& t);
// Sets lib/aerial_perspective.glsl's uniforms and binds its two tables.
void bind_aerial_perspective(const ShaderProgram& p, const AtmosphereTextures& t);

}  // namespace nimbus::render

// The physical sky's tables (render/media/atmosphere_tables.hpp) as textures: the sky view for
// the sky behind the scene (shaders/lib/sky.glsl), the aerial perspective for the haze in front
// of the clouds (shaders/lib/aerial_perspective.glsl). RGB32F, read with texelFetch and the
// tables' own bilinear weights, so the GPU reads what the CPU reads.
#pragma once
#include <memory>

#include "nimbus/render/media/atmosphere_tables.hpp"
#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/gl/uniform_blocks.hpp"

namespace nimbus::render {

class ShaderProgram;

struct AtmosphereTextures {
  std::shared_ptr<const AtmosphereTables> tables;
  GlTexture sky_view, aerial_scattering, aerial_transmittance;
};

// Uploads the tables (a current GL context is needed).
AtmosphereTextures upload_atmosphere(std::shared_ptr<const AtmosphereTables> tables);

// lib/sky_block.glsl's values: `sky`'s gradient (none: no sky), and the physical sky's when its
// tables are uploaded (`tables`, else none: the gradient, no aerial perspective).
SkyBlock sky_block(const Sky* sky, const AtmosphereTextures* tables);
// Binds the tables' textures: the sky view to UNIT_SKY_VIEW, the aerial perspective's two to
// theirs.
void bind_atmosphere_textures(const AtmosphereTextures& t);

}  // namespace nimbus::render

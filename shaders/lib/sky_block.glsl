// The scene's sky as its shaders read it (uniform_blocks.hpp's SkyBlock, filled by sky_block,
// atmosphere_textures.hpp): its gradient, and the physical sky's tables, the sky view behind the
// scene (lib/sky.glsl) and the aerial perspective in front of it (lib/aerial_perspective.glsl).
#ifndef NIMBUS_SKY_BLOCK_GLSL
#define NIMBUS_SKY_BLOCK_GLSL
#include "lib/contract.glsl"
layout(std140, binding = BLOCK_SKY) uniform SkyBlock {
  vec3 zenith;                  // the gradient's zenith radiance, W sr^-1 m^-2 per channel
  int has_sky;                  // 1: the scene has a sky
  vec3 horizon;                 // the gradient's horizon radiance
  int physical;                 // 1: the sky-view table; 0: the gradient
  vec3 sun;                     // the physical sky's direction to the sun, unit
  float cos_horizon;            // cos of the horizon's zenith angle at the viewer
  float distance_m;             // the sky's distance, metres
  int aerial_on;                // 1: the aerial perspective's tables are bound
  float aerial_max_distance_m;  // the tables' reach
} sky_state;
#endif

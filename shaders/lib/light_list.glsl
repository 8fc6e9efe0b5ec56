// The scene's lights as every pass sees them (LightsBlock of lib/contract.glsl; C++:
// render/gl/uniform_blocks.hpp): up to MAX_POINT_LIGHTS point lights and the sun.
#ifndef NIMBUS_LIGHT_LIST_GLSL
#define NIMBUS_LIGHT_LIST_GLSL
#include "lib/contract.glsl"
layout(std140, binding = BLOCK_LIGHTS) uniform LightsBlock {
  vec4 point_position[MAX_POINT_LIGHTS];   // xyz: metres
  vec4 point_intensity[MAX_POINT_LIGHTS];  // rgb: W/sr per channel
  vec3 to_sun;                             // unit direction towards the sun
  int point_count;                         // point lights in use
  vec3 sun_irradiance;                     // W/m^2 per channel
  int has_sun;                             // 1: the sun shines
} lights;
#endif

// The light a shadow map is made for, and the limits of the shadow volume's skirts built from it
// (uniform_blocks.hpp's ShadowMapBlock): shadow_distance.frag.glsl and
// shadow_volume_build.comp.glsl.
#ifndef NIMBUS_SHADOW_MAP_BLOCK_GLSL
#define NIMBUS_SHADOW_MAP_BLOCK_GLSL
#include "lib/contract.glsl"
layout(std140, binding = BLOCK_SHADOW_MAP) uniform ShadowMapBlock {
  vec3 origin;          // the lamp's position, or the sun map's corner (a point on its plane)
  int mode;             // SHADOW_POINT_LIGHT (cube map array layer `layer`) or SHADOW_SUN
  vec3 to_sun;          // unit, towards the sun (light propagates along -to_sun)
  int layer;
  vec3 axis_x;          // the sun map's width vector, metres
  int res;              // texels per side (of each cube face)
  vec3 axis_y;          // the sun map's height vector, metres
  float rel_threshold;  // relative distance jump that makes a silhouette
  float max_distance;   // skirts end here (metres): beyond it the airlight is negligible
  uint max_quads;
} shadow_map;
#endif

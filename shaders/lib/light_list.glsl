// The scene's lights as every pass sees them (LightsBlock of lib/contract.glsl; C++:
// render/gl/uniform_blocks.hpp): up to MAX_POINT_LIGHTS lamps (point lights, spots among them)
// and the sun. SPOTS 0 (a scene without spots: render::any_spot) compiles the cones out: every
// lamp shines every way, at the speed of a scene that never had spots (on llvmpipe the spot
// code alone, never run, cost a third more time in the shafts pass). Default 1: correct for any
// lights.
#ifndef NIMBUS_LIGHT_LIST_GLSL
#define NIMBUS_LIGHT_LIST_GLSL
#ifndef SPOTS
#define SPOTS 1
#endif
#include "lib/contract.glsl"
#include "lib/spot_cone.glsl"
layout(std140, binding = BLOCK_LIGHTS) uniform LightsBlock {
  vec4 point_position[MAX_POINT_LIGHTS];   // xyz: metres
  vec4 point_intensity[MAX_POINT_LIGHTS];  // rgb: W/sr per channel
  vec4 point_spot[MAX_POINT_LIGHTS];       // xyz: unit axis (propagation); w = 1 for a spot, 0 for a lamp
  vec4 point_cone[MAX_POINT_LIGHTS];       // a spot: x = cos(outer), y = cos(inner)
  vec3 to_sun;                             // unit direction towards the sun
  int point_count;                         // point lights in use
  vec3 sun_irradiance;                     // W/m^2 per channel
  int has_sun;                             // 1: the sun shines
} lights;

// Lamp i's weight for the unit propagation direction u (from the lamp): 1 for a lamp that is
// not a spot, else its cone's (render::spot_weight).
float lamp_spot_weight(int i, vec3 u) {
#if SPOTS
  if (lights.point_spot[i].w > 0.5)
    return spot_cone_weight(dot(u, lights.point_spot[i].xyz), lights.point_cone[i].x, lights.point_cone[i].y);
#endif
  return 1.0;
}

// Whether lamp i is a spot (always false with SPOTS 0).
bool lamp_is_spot(int i) {
#if SPOTS
  return lights.point_spot[i].w > 0.5;
#else
  return false;
#endif
}
#endif

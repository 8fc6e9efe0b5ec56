// The scene's lights as every pass sees them (LightsBlock of lib/contract.glsl; C++:
// render/gl/uniform_blocks.hpp): up to MAX_POINT_LIGHTS lamps (point lights, spots among them)
// and the sun, each a LightRecord (lib/light_record.glsl). SPOTS 0 (a scene without spots: render::any_spot) compiles the cones out: every
// lamp shines every way, at the speed of a scene that never had spots (on llvmpipe the spot
// code alone, never run, cost a third more time in the shafts pass). Default 1: correct for any
// lights.
#ifndef NIMBUS_LIGHT_LIST_GLSL
#define NIMBUS_LIGHT_LIST_GLSL
#ifndef SPOTS
#define SPOTS 1
#endif
#include "lib/contract.glsl"
#include "lib/light_eval.glsl"
layout(std140, binding = BLOCK_LIGHTS) uniform LightsBlock {
  LightRecord lamp[MAX_POINT_LIGHTS];  // the lamps (point lights, spots among them)
  LightRecord sun;                     // the sun (its irradiance 0 when has_sun is 0)
  int lamp_count;                      // lamps in use
  int has_sun;                         // 1: the sun shines
} lights;

// Lamp i's weight for the unit propagation direction u (from the lamp): 1 for a lamp that is
// not a spot, else its cone's (render::spot_weight).
float lamp_spot_weight(int i, vec3 u) {
#if SPOTS
  return light_spot_weight(lights.lamp[i], u);
#else
  return 1.0;
#endif
}

// Whether lamp i is a spot (always false with SPOTS 0).
bool lamp_is_spot(int i) {
#if SPOTS
  return lights.lamp[i].spot.w > 0.5;
#else
  return false;
#endif
}
#endif

// The lamp that lights the slicer's current pass (LAMP 1; light.hpp: a point light, or a
// spot): where the light comes from at a world point, and how much arrives there unshadowed,
// by the one light evaluation (lib/light_eval.glsl: I w / max(r, r_min)^2).
#ifndef NIMBUS_CLOUD_LAMP_GLSL
#define NIMBUS_CLOUD_LAMP_GLSL

#include "lib/cloud_light_block.glsl"  // the lamp: slice_light.light

// The lamp's position, metres.
vec3 lamp_position() { return slice_light.light.position.xyz; }

// The light's propagation direction at x (unit, from the lamp to x).
vec3 lamp_propagation(vec3 x) { return light_propagation(slice_light.light, x); }

// Unshadowed irradiance at x, given the propagation direction l there.
vec3 lamp_irradiance(vec3 x, vec3 l) { return light_irradiance(slice_light.light, x, l); }

#endif

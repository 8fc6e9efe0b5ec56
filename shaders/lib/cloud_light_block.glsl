// The light of the slicer's current pass (light.hpp's Light, one pass each: the sun, a
// lamp or a spot) with the pass's slicing geometry, as both slice programs see it
// (SliceLightBlock of lib/contract.glsl; C++: render/gl/uniform_blocks.hpp, filled by
// render/clouds/src/cloud_light_pass.cpp). One sign convention with LightsBlock: the sun's
// direction points towards the sun; light propagates along -to_sun.
#ifndef NIMBUS_CLOUD_LIGHT_BLOCK_GLSL
#define NIMBUS_CLOUD_LIGHT_BLOCK_GLSL
#include "lib/contract.glsl"
layout(std140, binding = BLOCK_SLICE_LIGHT) uniform SliceLightBlock {
  mat4 world_to_light_uv;   // the sun: world -> its orthographic light buffer's (u, w) in [0, 1]
  mat4 world_to_lamp_clip;  // a lamp: world -> its perspective light buffer's clip coordinates
  vec3 slice_axis;          // s, unit
  float spacing_m;          // d, slice spacing along s
  vec3 to_sun;              // the sun: unit, towards it
  float light_slab_m;       // the sun: d / |dot(l, s)|, a slab's thickness along the light
  vec3 sun_irradiance;      // the sun: E, W m^-2 per channel
  float lamp_min_distance;  // a lamp: metres, > 0
  vec3 lamp_position;       // a lamp: metres
  vec3 lamp_intensity;      // a lamp: W/sr per channel
  vec4 lamp_spot;           // a lamp: unit axis (propagation), w = 1 for a spot, 0 for a lamp
  vec2 luv_eye;             // the sun: the eye's light-buffer coordinates
  vec2 lamp_cos;            // a spot: cos(outer), cos(inner) of its cone
} slice_light;
#endif

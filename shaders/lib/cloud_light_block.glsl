// The light of the slicer's current pass (light.hpp's Light, one pass each: the sun, a
// lamp or a spot) with the pass's slicing geometry, as both slice programs see it
// (SliceLightBlock of lib/contract.glsl; C++: render/gl/uniform_blocks.hpp, filled by
// render/clouds/src/cloud_light_pass.cpp). The light is a LightRecord (lib/light_record.glsl), as
// each of LightsBlock's lights is.
#ifndef NIMBUS_CLOUD_LIGHT_BLOCK_GLSL
#define NIMBUS_CLOUD_LIGHT_BLOCK_GLSL
#include "lib/contract.glsl"
#include "lib/light_eval.glsl"
layout(std140, binding = BLOCK_SLICE_LIGHT) uniform SliceLightBlock {
  mat4 world_to_light_uv;   // the sun: world -> its orthographic light buffer's (u, w) in [0, 1]
  mat4 world_to_lamp_clip;  // a lamp: world -> its perspective light buffer's clip coordinates
  vec3 slice_axis;          // s, unit
  float spacing_m;          // d, slice spacing along s
  LightRecord light;        // the pass's light: the sun or a lamp (a spot among them)
  vec2 luv_eye;             // the sun: the eye's light-buffer coordinates
  float light_slab_m;       // the sun: d / |dot(l, s)|, a slab's thickness along the light
} slice_light;
#endif

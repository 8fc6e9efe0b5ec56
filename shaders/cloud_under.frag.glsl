#version 450 core
// Puts the far copies of periodic tiles (render/core cloud_tiles.hpp) under the near clouds in the
// slicer's eye buffer: drawn with the "under" blend, eye += (1 - eye alpha) far, for the
// premultiplied radiance and, UNDERLAY 1, the alpha-weighted distances that the composite reads
// (cloud_slice.frag.glsl's second output). Every ray meets the near clouds first.
#include "lib/contract.glsl"
#ifndef UNDERLAY
#define UNDERLAY 0
#endif
layout(binding = UNIT_CLOUD_COLOR) uniform sampler2D u_pass;  // RGBA32F, the far pass's radiance and alpha
#if UNDERLAY
layout(binding = UNIT_CLOUD_DISTANCE) uniform sampler2D u_pass_distance;  // RGBA32F, its distances
layout(location = 1) out vec4 o_distance;
#endif
layout(location = 0) out vec4 o_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  o_color = texelFetch(u_pass, p, 0);
#if UNDERLAY
  o_distance = texelFetch(u_pass_distance, p, 0);
#endif
}

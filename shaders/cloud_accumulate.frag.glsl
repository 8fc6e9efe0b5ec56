#version 450 core
// Adds one light's pass of the half-angle slicer to the clouds' eye buffer: the in-scattered
// radiance (RGB) of every light sums (single scattering is linear in the source), the coverage
// (alpha) is the first pass's. Drawn with additive blending and alpha writes masked.
#include "lib/contract.glsl"
layout(binding = UNIT_CLOUD_COLOR) uniform sampler2D u_pass;  // RGBA32F, the light's premultiplied radiance
layout(location = 0) out vec4 o_color;

void main() {
  o_color = vec4(texelFetch(u_pass, ivec2(gl_FragCoord.xy), 0).rgb, 0.0);
}

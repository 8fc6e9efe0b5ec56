#version 450 core
// Kniss et al.'s forward-scattering blur of the light buffer (2003): each slice spreads the
// optical depth before it by a cone's disk, here the 5-tap kernel with the disk's variance per
// axis (radius^2 / 4): neighbours at u_step texels weigh u_weight each (at most 1/4), so blurs
// repeated slice after slice grow with depth. Additive slice polygons follow in the same buffer.
#include "lib/contract.glsl"
layout(binding = UNIT_LIGHT_BUFFER) uniform sampler2D u_previous;  // R32F optical depth
uniform ivec2 u_step;          // texels along u and w, >= 1
uniform vec2 u_weight;         // per neighbour along u and w
layout(location = 0) out vec4 o_tau;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_previous, 0) - 1;
  ivec2 du = ivec2(u_step.x, 0);
  ivec2 dw = ivec2(0, u_step.y);
  float c = texelFetch(u_previous, p, 0).r;
  float su = texelFetch(u_previous, clamp(p - du, ivec2(0), last), 0).r +
             texelFetch(u_previous, clamp(p + du, ivec2(0), last), 0).r;
  float sw = texelFetch(u_previous, clamp(p - dw, ivec2(0), last), 0).r +
             texelFetch(u_previous, clamp(p + dw, ivec2(0), last), 0).r;
  o_tau = vec4((1.0 - 2.0 * u_weight.x - 2.0 * u_weight.y) * c + u_weight.x * su + u_weight.y * sw, 0.0, 0.0, 0.0);
}

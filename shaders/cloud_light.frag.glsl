#version 450 core
// Light pass of the half-angle slicer (Kniss et al. 2003): one cloud's polygon of one slice adds
// the optical depth of its slab along the light, sigma_t rho d / |dot(l, s)|, into the light
// buffer (additive blending), so later slices see exp(-tau) of everything before them.
#include "lib/cloud_block.glsl"
in vec3 v_tc;
layout(binding = UNIT_CLOUD_DENSITY) uniform sampler3D u_density;  // border 0 outside the active box
layout(location = 0) out vec4 o_tau;

void main() {
  float rho = max(texture(u_density, v_tc).r, 0.0);
  o_tau = vec4(rho * cloud.tau_per_density, 0.0, 0.0, 0.0);
}

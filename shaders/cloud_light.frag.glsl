#version 450 core
// Light pass of the half-angle slicer (Kniss et al. 2003): one cloud's polygon of one slice adds
// the optical depth of its slab along the light, sigma_t rho d / |dot(l, s)|, into the light
// buffer (additive blending), so later slices see exp(-tau) of everything before them.
#include "lib/cloud_block.glsl"
in vec3 v_tc;
#include "lib/cloud_density.glsl"
layout(location = 0) out vec4 o_tau;

void main() {
  float rho = cloud_density(v_tc);
  o_tau = vec4(rho * cloud.tau_per_density, 0.0, 0.0, 0.0);
}

#version 450 core
// Light pass of the half-angle slicer (Kniss et al. 2003): one cloud's polygon of one slice adds
// the optical depth of its slab along the light, sigma_t rho d / |dot(l, s)|, into the light
// buffer (additive blending), so later slices see exp(-tau) of everything before them.
// LAMP 1: the buffer is the lamp's perspective view (a texel is a ray from the lamp), and the
// slab along that ray is d / dot(l, s) with l the ray's direction; the part of a slice on the
// lamp's near side (dot(x - lamp, s) <= 0) is not on the lamp's rays beyond it and adds nothing.
#include "lib/cloud_block.glsl"
#include "lib/cloud_light_block.glsl"
#ifndef LAMP
#define LAMP 0
#endif
in vec3 v_tc;
#include "lib/cloud_density.glsl"
#if LAMP
#include "lib/cloud_lamp.glsl"
in vec3 v_world;
#endif
layout(location = 0) out vec4 o_tau;

void main() {
  float rho = cloud_density(v_tc);
#if LAMP
  vec3 l = lamp_propagation(v_world);
  float ls = dot(l, slice_light.slice_axis);
  if (dot(v_world - lamp_position(), slice_light.slice_axis) <= 0.0) discard;
  o_tau = vec4(rho * cloud.sigma_t * slice_light.spacing_m / max(ls, 1.0e-3), 0.0, 0.0, 0.0);
#else
  o_tau = vec4(rho * cloud.tau_per_density, 0.0, 0.0, 0.0);
#endif
}

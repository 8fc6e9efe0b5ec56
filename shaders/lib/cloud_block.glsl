// One cloud as the slicer's passes and the cloud shadow map see it (CloudBlock of
// lib/contract.glsl; C++: render/gl/uniform_blocks.hpp), bound per cloud as a range of one buffer.
#ifndef NIMBUS_CLOUD_BLOCK_GLSL
#define NIMBUS_CLOUD_BLOCK_GLSL
#include "lib/contract.glsl"
layout(std140, binding = BLOCK_CLOUD) uniform CloudBlock {
  mat4 world_to_texture;   // world -> the density texture's coordinates (VolumeTexture)
  vec3 albedo;             // sigma_s / sigma_t per channel
  float sigma_t;           // extinction per unit density, per metre
  vec3 ambient;            // sky radiance on the cloud (0 when off), W sr^-1 m^-2
  float tau_per_density;   // sigma_t d / |dot(l, s)|: a slab's optical depth along the light per unit density
  vec3 phase;              // g_forward, g_back, forward weight
  float blend;             // weight of the next keyframe's density (lib/cloud_density.glsl)
  vec3 tc_eye;             // the eye's density-texture coordinates
  vec3 copy_offset_m;      // a periodic tile's copy: its offset from the cloud, metres (the light volume is the cloud's)
} cloud;
#endif

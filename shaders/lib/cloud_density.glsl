// A cloud's density at density-texture coordinates: its keyframe, mixed linearly with the next
// keyframe on the same box by CloudBlock.blend (render::sample_density does the same in double
// precision). Border 0 outside the box, as OpenVDB's trilinear sampler sees the background.
#ifndef NIMBUS_CLOUD_DENSITY_GLSL
#define NIMBUS_CLOUD_DENSITY_GLSL
#include "lib/cloud_block.glsl"
layout(binding = UNIT_CLOUD_DENSITY) uniform sampler3D u_density;
layout(binding = UNIT_CLOUD_DENSITY_NEXT) uniform sampler3D u_density_next;

float cloud_density(vec3 tc) {
  float rho = textureLod(u_density, tc, 0.0).r;
  // (1 - w) a + w b; a cloud without a next keyframe has blend 0 and costs one fetch.
  if (cloud.blend > 0.0) rho = mix(rho, textureLod(u_density_next, tc, 0.0).r, cloud.blend);
  return max(rho, 0.0);
}
#endif

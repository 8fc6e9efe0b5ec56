#version 450 core
// Nearest and farthest shadow-volume crossing in front of the visible surface, per pixel:
// attachment 0 is blended with MIN, attachment 1 with MAX (distances from the eye, metres).
#include "lib/camera_ray.glsl"
in vec3 v_world;
layout(binding = UNIT_SCENE_DISTANCE) uniform sampler2D u_surface_distance;  // 0 where the ray hits nothing
layout(location = 0) out float o_near;
layout(location = 1) out float o_far;
void main() {
  float t = length(v_world - camera.eye);
  float ts = texelFetch(u_surface_distance, ivec2(gl_FragCoord.xy), 0).r;
  if (ts > 0.0 && t >= ts * (1.0 - 1.0e-4)) discard;
  o_near = t;
  o_far = t;
}

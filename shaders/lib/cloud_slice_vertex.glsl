// The vertex stage of both slice passes (cloud_slice.vert.glsl, cloud_light.vert.glsl): a slice
// polygon's world position (metres) through u_view_proj (the camera's, or the light buffer's
// orthographic map), with its density-texture and light-buffer coordinates (affine in the
// position, so interpolated exactly; the sun's light buffer, SliceLightBlock).
#include "lib/cloud_block.glsl"
#include "lib/cloud_light_block.glsl"
layout(location = 0) in vec3 a_world;
uniform mat4 u_view_proj;
out vec3 v_world;
out vec3 v_tc;
out vec2 v_luv;

void main() {
  vec4 p = vec4(a_world, 1.0);
  v_world = a_world;
  v_tc = (cloud.world_to_texture * p).xyz;
  v_luv = (slice_light.world_to_light_uv * p).xy;
  gl_Position = u_view_proj * p;
}

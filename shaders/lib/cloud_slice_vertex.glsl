// The vertex stage of both slice passes (cloud_slice.vert.glsl, cloud_light.vert.glsl): a slice
// polygon's world position (metres) through u_view_proj (the camera's, or the light buffer's
// orthographic map), passed on for the 3D-texture and light-buffer lookups.
layout(location = 0) in vec3 a_world;
uniform mat4 u_view_proj;
out vec3 v_world;

void main() {
  v_world = a_world;
  gl_Position = u_view_proj * vec4(a_world, 1.0);
}

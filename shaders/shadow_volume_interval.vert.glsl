#version 450 core
// Shadow-volume skirts seen from the camera (positions in metres, from the build pass).
layout(location = 0) in vec4 a_position;
uniform mat4 u_view_proj;
out vec3 v_world;
void main() {
  v_world = a_position.xyz;
  gl_Position = u_view_proj * vec4(a_position.xyz, 1.0);
}

#version 450 core
// Shadow-volume skirts seen from the camera (positions in metres, from the build pass).
#include "lib/camera_ray.glsl"
layout(location = 0) in vec4 a_position;
out vec3 v_world;
void main() {
  v_world = a_position.xyz;
  gl_Position = camera.view_proj * vec4(a_position.xyz, 1.0);
}

// Scene geometry for every raster pass (surfaces, shadow maps): world-space position, normal
// and albedo out. Included by surface.vert.glsl and shadow_distance.vert.glsl.
layout(location = 0) in vec3 a_position;  // metres
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_albedo;
uniform mat4 u_view_proj;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_albedo;
void main() {
  v_world = a_position;
  v_normal = a_normal;
  v_albedo = a_albedo;
  gl_Position = u_view_proj * vec4(a_position, 1.0);
}

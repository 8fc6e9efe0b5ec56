// View ray through a pixel centre, exactly as nimbus::render::pixel_ray (camera.hpp): GL window
// coordinates have y up, so row 0 of the read-back (top) image is the last GL row.
uniform vec3 u_eye;            // metres
uniform vec3 u_forward;        // unit
uniform vec3 u_right_scaled;   // right * tan(fov/2)
uniform vec3 u_up_scaled;      // up * tan(fov/2) * height / width
uniform vec2 u_viewport;       // width, height in pixels

vec3 pixel_ray_dir(vec2 frag_coord) {
  vec2 ndc = 2.0 * frag_coord / u_viewport - 1.0;
  return normalize(u_forward + ndc.x * u_right_scaled + ndc.y * u_up_scaled);
}

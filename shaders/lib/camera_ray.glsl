// The camera (CameraBlock of lib/contract.glsl; C++: render/gl/uniform_blocks.hpp) and the view
// ray through a pixel centre, exactly as nimbus::render::pixel_ray (camera.hpp): GL window
// coordinates have y up, so row 0 of the read-back (top) image is the last GL row.
#include "lib/contract.glsl"
layout(std140, binding = BLOCK_CAMERA) uniform CameraBlock {
  mat4 view_proj;      // world -> clip
  vec3 eye;            // metres
  float near_m;        // the near plane, metres
  vec3 forward;        // unit
  vec3 right_scaled;   // right * tan(fov/2)
  vec3 up_scaled;      // up * tan(fov/2) * height / width
  vec2 viewport;       // width, height in pixels
  vec2 pixel_offset;   // every ray's sub-pixel shift, GL window pixels (y up)
} camera;

vec3 pixel_ray_dir(vec2 frag_coord) {
  vec2 ndc = 2.0 * (frag_coord + camera.pixel_offset) / camera.viewport - 1.0;
  return normalize(camera.forward + ndc.x * camera.right_scaled + ndc.y * camera.up_scaled);
}

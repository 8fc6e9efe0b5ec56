#version 450 core
// The light volume's radiance toward this frame's eye (lib/cloud_light_volume.glsl) at every cell
// centre, for the slicer's eye pass to interpolate (light_volume_radiance): in the left half
// (fluence RGB x the angular part toward the eye, mean fluence), in the right (gradient,
// mean - h) for eq. MS-4's fit. Made once per frame: the eye moves, and the volume is mixed and
// moved with the keyframes and the wind.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#include "lib/contract.glsl"
#include "lib/cloud_light_volume.glsl"
layout(rgba32f, binding = IMAGE_LIGHT_RADIANCE) writeonly uniform image3D u_radiance;
uniform vec3 u_eye;  // metres

void main() {
  ivec3 cell = ivec3(gl_GlobalInvocationID);
  ivec3 cells = ivec3(lv_grid.cells);
  if (any(greaterThanEqual(cell, cells))) return;
  vec3 u = vec3(cell) + 0.5;
  LightVolumeCell v = light_volume_cell(cell);
  float mean = (v.a.r + v.a.g + v.a.b) / 3.0;
  vec4 lit = vec4(0.0);
  if (mean > 0.0) {
    vec3 to_eye = u_eye - (lv_grid.world_min + u * lv_grid.cell_m);
    float dist = length(to_eye);
    to_eye = dist > 0.0 ? to_eye / dist : -lv_grid.light_dir;
    lit = vec4(v.a.rgb * light_volume_angular(v, mean, to_eye, u_lr_phase), mean);
  }
  imageStore(u_radiance, cell, lit);
  imageStore(u_radiance, cell + ivec3(cells.x, 0, 0), vec4(v.grad, mean - v.c.w));
}

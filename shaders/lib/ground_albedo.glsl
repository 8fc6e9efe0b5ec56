// The ground's albedo texture (render/scene/ground_albedo.hpp) on the GPU: the land use at the
// long period times the detail's brightness at the short one, each read by GROUND_TAPS taps
// along the pixel's footprint at the mip level of its share (lib/ground_albedo_map.glsl), as
// render::ground_albedo reads it on the CPU.
#include "lib/contract.glsl"
#include "lib/ground_albedo_map.glsl"
layout(binding = UNIT_GROUND_ALBEDO) uniform sampler2D u_ground_albedo;  // RGB32F, mipmapped, repeating
// The texture's scales (uniform_blocks.hpp's GroundAlbedoBlock).
layout(std140, binding = BLOCK_GROUND_ALBEDO) uniform GroundAlbedoBlock {
  vec2 period_m;         // the land use's period, the detail's, metres
  float texels;          // texels per side of level 0
  float mean_luminance;  // the texture's mean luminance
} ground_texture;

// p: the ground point (world, metres); dir: unit view direction; distance_m: from the eye;
// pixel_angle_rad: the angle one pixel subtends.
vec3 ground_albedo(vec3 p, vec3 dir, float distance_m, float pixel_angle_rad) {
  vec2 fp = ground_footprint(dir.y, distance_m, pixel_angle_rad);
  vec2 h = length(dir.xz) > 1.0e-12 ? normalize(dir.xz) : vec2(1.0, 0.0);
  float lod_land = ground_lod(fp, ground_texture.period_m.x / ground_texture.texels);
  float lod_detail = ground_lod(fp, ground_texture.period_m.y / ground_texture.texels);
  vec3 land = vec3(0.0), detail = vec3(0.0);
  for (int k = 0; k < GROUND_TAPS; ++k) {
    vec2 q = p.xz + h * ground_tap_offset(k, fp.y);
    land += textureLod(u_ground_albedo, q / ground_texture.period_m.x, lod_land).rgb;
    detail += textureLod(u_ground_albedo, q / ground_texture.period_m.y, lod_detail).rgb;
  }
  return ground_combine(land / float(GROUND_TAPS), detail / float(GROUND_TAPS), ground_texture.mean_luminance);
}

#version 450 core
// Surface pass: the radiance leaving each visible surface towards the eye, before the medium
// between them attenuates it (thesis eq. 24, Lambert), and its distance from the eye. With
// SURFACE_AIRLIGHT (default 1) each point light also adds the airlight the surface reflects
// (Sun eq. 13's L_p,a, lib/surface_airlight_texture.glsl): from the whole hemisphere, whichever
// way the surface faces and whether or not the light is shadowed (Sun's model has no occlusion).
// A spot lights the surface by its cone's weight towards it and reflects no airlight: the fog
// that would is spread around the lamp, mostly outside the cone, so no weight of the lamp's
// L_p,a fits; left out it costs under 3 % of a floor's radiance (docs/shafts.md, "Spots").
#ifndef SURFACE_AIRLIGHT
#define SURFACE_AIRLIGHT 1
#endif
in vec3 v_world;
in vec3 v_normal;
in vec3 v_albedo;
uniform float u_sigma_t;           // extinction, per metre
uniform float u_sigma_s;           // scattering, per metre (the surface airlight's)
#include "lib/contract.glsl"
// What is drawn now (uniform_blocks.hpp's SurfaceDrawBlock). The ground plane (is_ground 1) is
// shaded at its exact point on the pixel's ray (its quad reaches the horizon, where interpolated
// positions lose their metres), and with ground_textured its albedo is the texture's
// (lib/ground_albedo.glsl), not the vertices'.
layout(std140, binding = BLOCK_SURFACE_DRAW) uniform SurfaceDrawBlock {
  vec3 emissive_radiance;      // > 0 for light bulbs: their radiance, no shading
  int emissive;
  vec3 sky_irradiance_up;      // the sky's light on an upward surface, pi (zenith + horizon) / 2; 0 without a sky
  float normal_offset_texels;  // shadow lookups move this many texels along the normal
  int is_ground;
  float ground_height_m;
  int ground_textured;
} draw;
#include "lib/camera_ray.glsl"
#include "lib/lights.glsl"
#include "lib/ground_albedo.glsl"
#if SURFACE_AIRLIGHT
#include "lib/surface_airlight_texture.glsl"
#endif
layout(location = 0) out vec4 o_radiance;
layout(location = 1) out float o_distance;
void main() {
  vec3 n = normalize(v_normal);
  vec3 world = v_world;
  vec3 albedo = v_albedo;
  if (draw.is_ground != 0) {
    vec3 dir = pixel_ray_dir(gl_FragCoord.xy);
    float t = (draw.ground_height_m - camera.eye.y) / (abs(dir.y) > 1.0e-9 ? dir.y : -1.0e-9);
    if (t > 0.0) world = camera.eye + t * dir;
    if (draw.ground_textured != 0)
      albedo = ground_albedo(world, dir, length(world - camera.eye), 2.0 * length(camera.right_scaled) / camera.viewport.x);
  }
  vec3 to_eye = camera.eye - world;
  if (dot(n, to_eye) < 0.0) n = -n;  // two-sided
  vec3 L = vec3(0.0);
  if (draw.emissive != 0) {
    L = draw.emissive_radiance;
  } else {
    for (int i = 0; i < lights.lamp_count; ++i) {
      vec3 l = lights.lamp[i].position.xyz - world;
      float d = length(l);
      vec3 I = lights.lamp[i].power.rgb * lamp_spot_weight(i, -l / d);
#if SURFACE_AIRLIGHT
      if (!lamp_is_spot(i))
        L += albedo * lights.lamp[i].power.rgb * surface_airlight(u_sigma_t, u_sigma_s, 1.0, d, dot(n, l / d));
#endif
      float cos_s = max(dot(n, l / d), 0.0);
      if (cos_s <= 0.0) continue;
      // Normal offset against shadow acne on surfaces that are in the shadow maps.
      float v = point_visibility(i, world + n * (draw.normal_offset_texels * d * scene_shadows.point_texel_angle));
      L += albedo / 3.14159265358979 * I * cos_s * exp(-u_sigma_t * d) / (d * d) * v;
    }
    if (lights.has_sun != 0) {
      float cos_s = max(dot(n, lights.sun.position.xyz), 0.0);
      if (cos_s > 0.0)
        L += albedo / 3.14159265358979 * lights.sun.power.rgb * cos_s * sun_surface_visibility(world + n * (draw.normal_offset_texels * scene_shadows.sun_texel_m));
    }
    // The sky, uniform at its mean, seen by the share (1 + n.y) / 2 (render::sky_irradiance).
    L += albedo / 3.14159265358979 * draw.sky_irradiance_up * (0.5 * (1.0 + clamp(n.y, -1.0, 1.0)));
  }
  o_radiance = vec4(L, 1.0);
  o_distance = length(to_eye);
}

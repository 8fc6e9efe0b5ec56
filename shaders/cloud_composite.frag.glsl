#version 450 core
// The clouds over the scene (cloud_renderer.hpp, SceneUnderlay): out = scene (1 - A) + C +
// sum_i w_i A_fog(0, t_i), C the fog-attenuated clouds, A their alpha, w_i the slices' weights.
// Each slice sees the fog's unshadowed airlight in front of it; summed under the clouds'
// blending, the fog in front is counted once. For the sun A_fog(0, t) = sigma_s p E
// (1 - e^{-sigma t}) / sigma, so the sum is exact from the accumulated weighted spans; lamps
// (spots among them, lib/lamp_airlight.glsl) take A * A_fog(0, D) at the alpha-weighted mean
// distance D. With a physical sky the air's aerial perspective (lib/aerial_perspective.glsl)
// hazes the clouds at D and the surfaces at their distance: x -> x T_air + S_air (weighted by
// alpha for the clouds), and beyond the table's reach tends to the horizon sky
// (lib/far_ground_haze.glsl), so the ground meets the sky at the horizon. Output alpha 1. Second output, for carrying the frame into the next
// (temporal_frame.hpp, pixel_depths.hpp): the distance to what carries the pixel's detail (D
// where A >= 1/2 or where clouds are over the sky, else the surface's, else 0 for the sky) and
// 1 when that is the clouds'.
in vec2 uv;
#include "lib/camera_ray.glsl"
#include "lib/light_list.glsl"
#include "lib/lamp_airlight.glsl"
#include "lib/aerial_perspective.glsl"
#include "lib/sky.glsl"
layout(binding = UNIT_SCENE_COLOR) uniform sampler2D u_scene_color;  // RGBA32F premultiplied scene radiance
layout(binding = UNIT_CLOUD_COLOR) uniform sampler2D u_cloud_color;  // premultiplied cloud radiance, alpha
layout(binding = UNIT_SCENE_DISTANCE) uniform sampler2D u_scene_distance;  // R32F metres to the visible surface, 0 = none
layout(binding = UNIT_CLOUD_DISTANCE) uniform sampler2D u_cloud_distance;  // (sum w t, sum w (1 - e^{-sigma t}) / sigma, 0, alpha)
uniform float u_sigma_t;             // fog extinction, per metre
uniform float u_sigma_s;             // fog scattering, per metre
uniform int u_phase_kind;            // PHASE_* code
uniform float u_phase_g;
#include "lib/far_ground_haze.glsl"
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec2 o_depth;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec3 scene = texelFetch(u_scene_color, px, 0).rgb;
  vec4 cloud = texelFetch(u_cloud_color, px, 0);
  vec4 weighted = texelFetch(u_cloud_distance, px, 0);
  float A = clamp(cloud.a, 0.0, 1.0);
  float D = weighted.a > 1.0e-12 ? max(weighted.r / weighted.a, 0.0) : 0.0;
  vec3 dir = pixel_ray_dir(gl_FragCoord.xy);
  vec3 air = vec3(0.0);
  for (int i = 0; i < lights.lamp_count; ++i)
    air += (A * lights.lamp[i].power.rgb) *
           lamp_segment_airlight(i, camera.eye, dir, 0.0, D, u_sigma_t, u_sigma_s, u_phase_kind, u_phase_g);
  float sun = float(lights.has_sun) * u_sigma_s * phase_value(u_phase_kind, u_phase_g, dot(-lights.sun.position.xyz, -dir));
  air += lights.sun.power.rgb * (sun * max(weighted.g, 0.0));
  vec3 clouds = cloud.rgb;
  if (sky_state.aerial_on != 0) {
    vec3 S, T;
    if (A > 0.0) {
      aerial_perspective(dir, D, S, T);
      clouds = clouds * T + A * S;
    }
    float surface = texelFetch(u_scene_distance, px, 0).r;
    if (surface > 0.0) {
      surface_haze(dir, surface, S, T);
      scene = scene * T + S;
    }
  }
  float surface_m = max(texelFetch(u_scene_distance, px, 0).r, 0.0);
  bool on_clouds = D > 0.0 && (A >= 0.5 || (surface_m == 0.0 && A > 1.0e-3));
  o_depth = vec2(on_clouds ? D : surface_m, on_clouds ? 1.0 : 0.0);
  o_color = vec4(scene * (1.0 - A) + clouds + air, 1.0);
}

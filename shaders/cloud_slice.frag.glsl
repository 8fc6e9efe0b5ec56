#version 450 core
// Eye pass of the half-angle slicer (Kniss et al. 2003): one cloud's polygon of one slice, lit
// from the light buffer (optical depth toward the light of the slices before it) and composited
// into the eye buffer with the energy-conserving step integral (Hillaire 2015): colour =
// (S / sigma_t) (1 - exp(-sigma_t rho dt)). dt = d / |dot(ray, s)| per fragment (less for the
// slab around the eye); the sample is jittered along the ray within its slab (blue noise), which
// hides slice banding. The sample
// x = v_world + k q (q = v_world - eye) has texture coordinates (1 + k) v - k (those of the eye),
// as both maps are affine: no matrix per fragment.
// UNDERLAY 1: cut at the scene's surfaces, attenuated by the fog in front, and
// (alpha t, alpha (1 - exp(-sigma_fog t)) / sigma_fog, 0, alpha) into the second output for the
// fog's airlight in front of the clouds (cloud_composite.frag.glsl). OCTAVES: extra
// multiple-scattering octaves (0 = single scattering). MS_VOLUME 1: the light volume's
// in-scattered radiance of scattered light (lib/cloud_light_volume.glsl) is added to the exact
// single scattering at each sample; MS_VOLUME 2: the same from the frame's radiance toward the
// eye (light_volume_radiance, one cell-centre evaluation per frame instead of one per sample).
// LAMP 1: the light is a lamp (lib/cloud_lamp.glsl): per fragment its direction, its
// irradiance (inverse square, spot cone) and the slab along its ray, d / dot(l, s); the light
// buffer is its perspective view (slice_light.world_to_lamp_clip). A sample on the lamp's near side of
// the slices (the lamp among them) reads no shadow from the buffer, only its own slab's.
// The camera, the cloud and the pass's light (lib/camera_ray.glsl, lib/cloud_block.glsl,
// lib/cloud_light_block.glsl) are uniform blocks.
#include "lib/camera_ray.glsl"
#include "lib/cloud_density.glsl"
#include "lib/cloud_phase.glsl"
#include "lib/cloud_light_block.glsl"
#ifndef UNDERLAY
#define UNDERLAY 0
#endif
#ifndef OCTAVES
#define OCTAVES 0
#endif
#ifndef MS_VOLUME
#define MS_VOLUME 0
#endif
#ifndef LAMP
#define LAMP 0
#endif
#if MS_VOLUME
#include "lib/cloud_light_volume.glsl"
#endif
#if LAMP
#include "lib/cloud_lamp.glsl"
#endif
in vec3 v_world;
in vec3 v_tc;
in vec2 v_luv;
uniform vec3 u_octave_abc;        // occlusion a, contribution b, eccentricity c
layout(binding = UNIT_LIGHT_BUFFER) uniform sampler2D u_light;  // R32F optical depth of the slices before this one
layout(binding = UNIT_JITTER) uniform sampler2D u_jitter;  // blue-noise tile (power-of-two side), values in (0, 1)
uniform ivec2 u_jitter_offset;    // this frame's tile shift, pixels (>= 0)
uniform float u_jitter_shift;     // this frame's shift of the values, modulo 1
uniform float u_jitter_on;        // 1: jitter; 0: the slab's middle
#if UNDERLAY
layout(binding = UNIT_SCENE_DISTANCE) uniform sampler2D u_scene_distance;  // R32F metres along the pixel's ray, 0 = no surface
uniform float u_fog_sigma_t;         // per metre
layout(location = 1) out vec4 o_distance;
#endif
layout(location = 0) out vec4 o_color;

void main() {
  vec3 q = v_world - camera.eye;
  float inv_len = inversesqrt(max(dot(q, q), 1.0e-30));
  float qs = dot(q, slice_light.slice_axis) * inv_len;  // dot(ray, s)
  float cos_rs = max(abs(qs), 1.0e-3);
  float dt = slice_light.spacing_m / cos_rs;
  ivec2 px = ivec2(gl_FragCoord.xy);
  ivec2 tile = textureSize(u_jitter, 0);
  float noise = fract(texelFetch(u_jitter, (px + u_jitter_offset) & (tile - 1), 0).r + u_jitter_shift);
  // This slab along the ray is [t - dt/2, t + dt/2] around the plane at t; where the plane
  // before it is behind the eye or the near plane (no fragment there), it reaches back to the eye.
  float t_plane = 1.0 / inv_len;
  float start = (t_plane - dt) * (dot(q, camera.forward) * inv_len) < camera.near_m ? 0.0 : t_plane - 0.5 * dt;
  float end = t_plane + 0.5 * dt;
#if UNDERLAY
  // A surface inside the slab ends it: the cloud behind the surface is hidden.
  float surface = texelFetch(u_scene_distance, px, 0).r;
  end = surface > 0.0 ? min(end, surface) : end;
#endif
  float slab = max(end - start, 0.0);
  float offset = start + mix(0.5, noise, u_jitter_on) * slab - t_plane;  // metres along the ray
  float k = offset * inv_len;
  float rho = cloud_density(v_tc + k * (v_tc - cloud.tc_eye));
  // Toward the light: the slices before this one, plus this slab up to the sample.
  float own = clamp(0.5 + offset * qs / slice_light.spacing_m, 0.0, 1.0);
#if LAMP
  vec3 x = v_world + k * q;
  vec3 light_dir = lamp_propagation(x);
  vec3 irradiance = lamp_irradiance(x, light_dir);
  vec4 lc = slice_light.world_to_lamp_clip * vec4(x, 1.0);
  bool beyond = dot(x - lamp_position(), slice_light.slice_axis) > 0.0 && lc.w > 0.0;
  float before = beyond ? texture(u_light, 0.5 + 0.5 * lc.xy / lc.w).r : 0.0;
  float tau = before + own * cloud.sigma_t * rho * slice_light.spacing_m / max(dot(light_dir, slice_light.slice_axis), 1.0e-3);
#else
  vec3 light_dir = -slice_light.light.position.xyz;  // l, the propagation direction
  vec3 irradiance = slice_light.light.power.rgb;
  float tau = texture(u_light, v_luv + k * (v_luv - slice_light.luv_eye)).r + own * cloud.sigma_t * rho * slice_light.light_slab_m;
#endif
  float od = cloud.sigma_t * rho * slab;
  float alpha = od < 1.0e-3 ? od * (1.0 - 0.5 * od) : 1.0 - exp(-od);
  float lit = cloud_octaves(cloud.phase, u_octave_abc, OCTAVES, -dot(light_dir, q) * inv_len, tau);
#if MS_VOLUME
#if MS_VOLUME == 2
  // made for this eye (a copy's toward the eye moved back by its offset) and the clouds' phase
  vec3 scattered = light_volume_radiance(v_world + k * q - cloud.copy_offset_m);
#else
  // A copy of a periodic tile reads its cloud's light volume where its cloud is.
  vec3 scattered = light_volume_inscatter(v_world + k * q - cloud.copy_offset_m, -q * inv_len, cloud.phase);
#endif
  vec3 color = cloud.albedo * (irradiance * (lit + scattered) + cloud.ambient) * alpha;  // (S / sigma_t) alpha
#else
  vec3 color = cloud.albedo * (irradiance * lit + cloud.ambient) * alpha;  // (S / sigma_t) alpha
#endif
#if UNDERLAY
  float t = max(t_plane + offset, 0.0);
  float y = u_fog_sigma_t * t;
  color *= exp(-y);
  float span = y < 1.0e-3 ? t * (1.0 - 0.5 * y) : (1.0 - exp(-y)) / u_fog_sigma_t;  // int_0^t e^{-sigma x} dx
  o_distance = vec4(alpha * t, alpha * span, 0.0, alpha);
#endif
  o_color = vec4(color, alpha);
}

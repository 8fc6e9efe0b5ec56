// The scene's lights (lib/light_list.glsl) and their shadow maps (distances in metres, see
// shadow_distance.frag.glsl).
#include "lib/light_list.glsl"
#include "lib/cloud_shadow.glsl"
layout(binding = UNIT_POINT_SHADOW) uniform samplerCubeArray u_point_shadow;  // layer = light index, R32F distance
layout(binding = UNIT_SUN_SHADOW) uniform sampler2D u_sun_shadow;  // R32F distance along -to_sun from the map's plane
// The maps' geometry and biases (uniform_blocks.hpp's SceneShadowsBlock).
layout(std140, binding = BLOCK_SCENE_SHADOWS) uniform SceneShadowsBlock {
  vec3 sun_origin;          // the sun map's corner (texel coords 0,0) on its plane
  float point_bias;         // relative distance bias (fraction of the distance)
  vec3 sun_axis_x;          // the sun map's width vector, metres
  float sun_bias;           // metres
  vec3 sun_axis_y;          // the sun map's height vector, metres
  float point_texel_angle;  // angular size of a cube-map texel at a face centre, radians
  float sun_texel_m;        // size of a sun-map texel, metres
} scene_shadows;

float point_visibility(int i, vec3 p) {
  vec3 v = p - lights.lamp[i].position.xyz;
  float d = length(v);
  float stored = textureLod(u_point_shadow, vec4(v, float(i)), 0.0).r;
  return d <= stored * (1.0 + scene_shadows.point_bias) ? 1.0 : 0.0;
}

float sun_visibility(vec3 p) {
  vec3 q = p - scene_shadows.sun_origin;
  vec2 st = vec2(dot(q, scene_shadows.sun_axis_x) / dot(scene_shadows.sun_axis_x, scene_shadows.sun_axis_x),
                 dot(q, scene_shadows.sun_axis_y) / dot(scene_shadows.sun_axis_y, scene_shadows.sun_axis_y));
  if (any(lessThan(st, vec2(0.0))) || any(greaterThan(st, vec2(1.0)))) return 1.0;
  float d = dot(q, -lights.sun.position.xyz);
  float stored = textureLod(u_sun_shadow, st, 0.0).r;
  return d <= stored + scene_shadows.sun_bias ? 1.0 : 0.0;
}

// The sun's light reaching p: the opaque shadow map times the clouds' transmittance.
float sun_light_visibility(vec3 p) {
  return sun_visibility(p) * cloud_transmittance(p);
}

// The same on a surface, with the penumbra of the sun's disc in the clouds' shadow
// (cloud_transmittance_soft): the fog's samples keep the one-tap form.
float sun_surface_visibility(vec3 p) {
  return sun_visibility(p) * cloud_transmittance_soft(p);
}

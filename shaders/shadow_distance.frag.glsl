#version 450 core
// Shadow maps store distances in metres: from a point light (cube faces), or along the sun's
// propagation direction from a plane in front of every occluder (orthographic map).
in vec3 v_world;
in vec3 v_normal;
in vec3 v_albedo;
#include "lib/shadow_map_block.glsl"  // mode, origin, to_sun
layout(location = 0) out float o_distance;
void main() {
  o_distance = (shadow_map.mode == SHADOW_POINT_LIGHT) ? length(v_world - shadow_map.origin)
                                                      : dot(v_world - shadow_map.origin, -shadow_map.to_sun);
}

#version 450 core
// Shadow maps store distances in metres: from a point light (cube faces), or along the sun's
// propagation direction from a plane in front of every occluder (orthographic map).
in vec3 v_world;
in vec3 v_normal;
in vec3 v_albedo;
#include "lib/contract.glsl"
uniform int u_mode;      // SHADOW_POINT_LIGHT or SHADOW_SUN
uniform vec3 u_origin;   // light position, or a point on the sun's plane
uniform vec3 u_to_sun;   // unit, towards the sun (light propagates along -u_to_sun)
layout(location = 0) out float o_distance;
void main() {
  o_distance = (u_mode == SHADOW_POINT_LIGHT) ? length(v_world - u_origin) : dot(v_world - u_origin, -u_to_sun);
}

// The physical sky's haze in front of things (atmosphere_tables.hpp, aerial perspective): the
// air's in-scattered radiance and transmittance from the viewer to a distance along a view
// direction, read through the tables' map (AtmosphereTable::trilinear) with the texture unit's
// own trilinear filter: two fetches instead of sixteen (its 8-bit weights differ from the CPU's
// by at most 1/256 of a texel step, well inside the tables' own error).
#include "lib/atmosphere_map.glsl"
#include "lib/sky_block.glsl"  // aerial_on, sun, cos_horizon, aerial_max_distance_m
layout(binding = UNIT_AERIAL_SCATTERING) uniform sampler3D u_aerial_scattering;      // RGB32F
layout(binding = UNIT_AERIAL_TRANSMITTANCE) uniform sampler3D u_aerial_transmittance;

// In-scattered radiance (W sr^-1 m^-2) and transmittance from the viewer to distance_m along dir.
void aerial_perspective(vec3 dir, float distance_m, out vec3 inscattered, out vec3 transmittance) {
  vec2 sh = vec2(sky_state.sun.x, sky_state.sun.z), dh = vec2(dir.x, dir.z);
  float ls = length(sh), ld = length(dh);
  float cos_phi = (ls > 1.0e-9 && ld > 1.0e-9) ? dot(sh, dh) / (ls * ld) : 1.0;
  vec2 uv = atm_view_uv(cos_phi, clamp(dir.y, -1.0, 1.0), sky_state.cos_horizon);
  vec3 c = vec3(uv * vec2(float(ATM_AP_W - 1), float(ATM_AP_H - 1)), atm_ap_depth(distance_m, sky_state.aerial_max_distance_m));
  vec3 tc = (c + 0.5) / vec3(ATM_AP_W, ATM_AP_H, ATM_AP_D);  // texel centres at k + 1/2
  inscattered = texture(u_aerial_scattering, tc).rgb;
  transmittance = texture(u_aerial_transmittance, tc).rgb;
}

// The haze in front of a surface beyond the aerial-perspective table's reach (the flat ground
// toward the horizon, up to thousands of kilometres away): the table ends at
// sky_state.aerial_max_distance_m, and past it the near-horizontal path is taken as a homogeneous
// medium, so its transmittance continues exponentially at the rate of a level path over the
// table's reach, T_h(R) (the ray's own may have met the tables' curved ground already: they
// are made for one viewer altitude), and its radiance tends to that of the horizon sky behind
// it (Koschmieder 1924: L = L0 T + L_h (1 - T)):
//   T(D) = T(R) T_h(R)^(D / R - 1),   S(D) = S(R) + (L_h - S(R)) (1 - T_h(R)^(D / R - 1)).
// L_h is the sky as the frame shows it just above the horizon in the same azimuth: the sky's
// radiance through the fog to the sky's distance plus the fog's unshadowed airlight
// (shafts.frag.glsl's sky pixels), so the ground meets the sky there with no step.
// Needs lib/aerial_perspective.glsl, lib/sky.glsl and lib/lamp_airlight.glsl, and the fog's
// u_sigma_t, u_sigma_s, u_phase_kind, u_phase_g.

// The frame's sky just above the horizon in dir's azimuth.
vec3 level_direction(vec3 dir) {
  return length(dir.xz) > 1.0e-9 ? vec3(normalize(dir.xz).x, 0.0, normalize(dir.xz).y) : vec3(1.0, 0.0, 0.0);
}

vec3 horizon_sky(vec3 dir) {
  vec3 h = level_direction(dir);
  float d = sky_state.distance_m;
  vec3 L = sky_radiance(h) * exp(-u_sigma_t * d);
  for (int i = 0; i < lights.lamp_count; ++i)
    L += lights.lamp[i].power.rgb *
         lamp_segment_airlight(i, camera.eye, h, 0.0, d, u_sigma_t, u_sigma_s, u_phase_kind, u_phase_g);
  if (lights.has_sun != 0)
    L += lights.sun.power.rgb *
         sun_segment_airlight(u_sigma_t, u_sigma_s, 1.0, dot(-lights.sun.position.xyz, -h), 0.0, d, u_phase_kind, u_phase_g);
  return L;
}

// In-scattered radiance and transmittance from the eye to a surface distance_m away along dir,
// at any distance.
void surface_haze(vec3 dir, float distance_m, out vec3 inscattered, out vec3 transmittance) {
  float R = sky_state.aerial_max_distance_m;
  aerial_perspective(dir, min(distance_m, R), inscattered, transmittance);
  if (distance_m <= R || sky_state.has_sky == 0) return;
  vec3 level_s, level_t;
  aerial_perspective(level_direction(dir), R, level_s, level_t);
  vec3 tail = pow(max(level_t, vec3(1.0e-30)), vec3(distance_m / R - 1.0));  // T_h(R)^(D/R - 1)
  inscattered += (horizon_sky(dir) - inscattered) * (1.0 - tail);
  transmittance *= tail;
}

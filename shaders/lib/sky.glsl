// The scene's sky (scene.hpp Sky): where rays that meet no surface end, and its radiance.
uniform int u_has_sky;
uniform vec3 u_sky_zenith;    // W sr^-1 m^-2 per channel
uniform vec3 u_sky_horizon;
uniform float u_sky_distance;  // metres

// horizon + (zenith - horizon) sqrt(max(dir.y, 0)), as sky_radiance in scene.cpp.
vec3 sky_radiance(vec3 dir) {
  return u_sky_horizon + (u_sky_zenith - u_sky_horizon) * sqrt(max(dir.y, 0.0));
}

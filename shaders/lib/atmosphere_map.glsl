// Where the physical sky's tables (render/media/atmosphere_tables.hpp, Hillaire 2020) keep each
// value: the map from a query (altitude, cosines, azimuth, distance) to texel coordinates, and
// the bilinear weights. Common subset of GLSL 4.50 and C++ (glm): render/core/src/
// atmosphere_tables.cpp compiles this file too, so the CPU lookups and the shaders share one map.
// Texel coordinates run from 0 to size - 1, with the first and last texels on the ends of each
// range (no half-texel offsets). Altitudes are passed instead of radii: r^2 - R^2 = h (2R + h)
// keeps its digits in float where r^2 - R^2 would not.
#ifndef NIMBUS_ATMOSPHERE_MAP_GLSL
#define NIMBUS_ATMOSPHERE_MAP_GLSL

const int ATM_TRANSMITTANCE_W = 256;  // cos of the zenith angle
const int ATM_TRANSMITTANCE_H = 64;   // altitude
const int ATM_MS_W = 64;              // cos of the sun's zenith angle
const int ATM_MS_H = 32;              // altitude
const int ATM_SKY_W = 192;            // azimuth from the sun
const int ATM_SKY_H = 108;            // view zenith angle
const int ATM_AP_W = 64;              // azimuth from the sun (as the sky view)
const int ATM_AP_H = 64;              // view zenith angle (as the sky view)
const int ATM_AP_D = 32;              // distance
const float ATM_PI = 3.14159265358979f;

// Bruneton (2017) transmittance map: x_mu = (d - d_min) / (d_max - d_min) with d the distance
// to the top along the ray, x_r = rho / H (rho the distance to the horizon, H its value at the
// top). Covers the rays that do not meet the ground. Returns texel coordinates.
vec2 atm_transmittance_coord(float bottom_m, float top_m, float altitude_m, float mu) {
  float h = clamp(altitude_m, 0.0f, top_m - bottom_m);
  float r = bottom_m + h;
  float H = sqrt((top_m - bottom_m) * (top_m + bottom_m));
  float rho = sqrt(h * (2.0f * bottom_m + h));
  // distance to the top, stably for both signs of mu
  float disc = (top_m - r) * (top_m + r) + r * r * mu * mu;
  float root = sqrt(max(disc, 0.0f));
  float d = mu >= 0.0f ? (top_m - r) * (top_m + r) / max(r * mu + root, 1.0e-6f) : root - r * mu;
  float d_min = top_m - r;
  float d_max = rho + H;
  float x_mu = clamp((d - d_min) / max(d_max - d_min, 1.0e-6f), 0.0f, 1.0f);
  float x_r = clamp(rho / H, 0.0f, 1.0f);
  return vec2(x_mu * float(ATM_TRANSMITTANCE_W - 1), x_r * float(ATM_TRANSMITTANCE_H - 1));
}

// Multiple-scattering map: u = (1 + sign(mu_s) sqrt|mu_s|) / 2 (columns crowd around the sun's
// horizon, where Psi_ms falls by orders of magnitude), v = sqrt(altitude / thickness) (rows
// crowd near the ground, where it changes fastest with altitude).
vec2 atm_ms_coord(float thickness_m, float altitude_m, float mu_s) {
  float m = clamp(mu_s, -1.0f, 1.0f);
  float u = clamp(0.5f + 0.5f * sign(m) * sqrt(abs(m)), 0.0f, 1.0f);
  float v = sqrt(clamp(altitude_m / thickness_m, 0.0f, 1.0f));
  return vec2(u * float(ATM_MS_W - 1), v * float(ATM_MS_H - 1));
}

// Sky-view map of a viewer at one altitude: u = sqrt(phi / pi), phi the azimuth from the sun
// (texels crowd toward the sun, where the aerosols' forward peak is), and v from the zenith
// (0) through the horizon (1/2, where the horizon's zenith angle theta_h puts it) to the
// nadir (1), with texels crowding quadratically toward the horizon:
// above it v = (1 - sqrt(1 - theta / theta_h)) / 2, below v = (1 + sqrt((theta - theta_h) / (pi - theta_h))) / 2.
// cos_phi: cosine of the azimuth from the sun; cos_theta: of the view zenith angle;
// cos_theta_h: of the horizon's zenith angle.
vec2 atm_view_uv(float cos_phi, float cos_theta, float cos_theta_h) {
  float phi = acos(clamp(cos_phi, -1.0f, 1.0f));
  float theta = acos(clamp(cos_theta, -1.0f, 1.0f));
  float theta_h = acos(clamp(cos_theta_h, -1.0f, 1.0f));
  float u = sqrt(phi / ATM_PI);
  float v = theta < theta_h ? 0.5f * (1.0f - sqrt(max(1.0f - theta / theta_h, 0.0f)))
                            : 0.5f * (1.0f + sqrt(clamp((theta - theta_h) / max(ATM_PI - theta_h, 1.0e-6f), 0.0f, 1.0f)));
  return vec2(clamp(u, 0.0f, 1.0f), clamp(v, 0.0f, 1.0f));
}

// Aerial-perspective depth map: w = sqrt(distance / max distance), in texels.
float atm_ap_depth(float distance_m, float max_distance_m) {
  return sqrt(clamp(distance_m / max_distance_m, 0.0f, 1.0f)) * float(ATM_AP_D - 1);
}

#endif

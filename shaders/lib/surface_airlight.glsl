// Airlight reflected by a Lambertian surface (Sun et al. section 4) from the tabulated G0:
//   L_p,a = (albedo / pi) (sigma_s I0 / Dsp) G0(Tsp, theta_s),  G0 = g e^{-Tsp} / (1 + Tsp),
// g read bilinearly from a table over (ln Tsp, theta_s) (render::SurfaceAirlightTable; the
// reduction and the table's error: render/media/include/nimbus/render/media/surface_airlight.hpp
// and docs/shafts.md). Common subset of GLSL 4.50 and C++ (glm): the table lookup itself is
// the caller's (texelFetch in lib/surface_airlight_texture.glsl, an array in
// render/media/src/surface_airlight_table.cpp), the rest is shared.
#ifndef NIMBUS_SURFACE_AIRLIGHT_GLSL
#define NIMBUS_SURFACE_AIRLIGHT_GLSL

const float SA_T_MIN = 1.0e-5f;   // the table's Tsp range (SurfaceAirlightTable::kTMin, kTMax)
const float SA_T_MAX = 100.0f;
const float SA_MAX_RESULT = 3.0e38f;

// Continuous table coordinates of (Tsp, cos theta_s): x over ln Tsp, y over theta_s in [0, pi],
// clamped to the table (nx columns, ny rows).
vec2 surface_airlight_coords(float T, float cos_theta_s, int nx, int ny) {
  float lo = log(SA_T_MIN);
  float x = (log(clamp(T, SA_T_MIN, SA_T_MAX)) - lo) / (log(SA_T_MAX) - lo) * float(nx - 1);
  float y = acos(clamp(cos_theta_s, -1.0f, 1.0f)) * (float(ny - 1) / 3.14159265f);
  return vec2(clamp(x, 0.0f, float(nx - 1)), clamp(y, 0.0f, float(ny - 1)));
}

// The lower-left node of the cell holding the coordinates.
ivec2 surface_airlight_cell(vec2 f, int nx, int ny) {
  return ivec2(min(int(f.x), nx - 2), min(int(f.y), ny - 2));
}

// Bilinear interpolation of the cell's four nodes g(i + di, j + dj) = gDIDJ.
float surface_airlight_bilinear(vec2 f, ivec2 cell, float g00, float g10, float g01, float g11) {
  vec2 d = f - vec2(cell);
  return mix(mix(g00, g10, d.x), mix(g01, g11, d.x), d.y);
}

// L_p,a per unit albedo from the interpolated g; 0 without scattering, finite and >= 0 for all
// finite non-negative inputs (Dsp is taken >= 1e-20 m; Tsp >= 87 underflows to 0).
float surface_airlight_radiance(float sigma_t, float sigma_s, float I0, float Dsp, float g) {
  if (!(sigma_s > 0.0f) || !(I0 > 0.0f)) return 0.0f;
  float D = max(Dsp, 1.0e-20f);
  float T = max(sigma_t, 0.0f) * D;
  if (!(T < 87.0f)) return 0.0f;
  float r = 0.318309886f * (sigma_s * I0 / D) * (exp(-T) / (1.0f + T)) * g;
  return r >= 0.0f ? min(r, SA_MAX_RESULT) : 0.0f;
}

#endif

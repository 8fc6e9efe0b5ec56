// Display encoding shared by the viewer's screen and its PNG screenshots: AgX (the default) or
// Stephen Hill's fit of the ACES RRT + sRGB ODT (BakingLab ACES.hlsl, 2016), then the sRGB
// transfer curve (IEC 61966-2-1).
// The same numbers as render/image/src/image_png.cpp (tests/gl/test_view_display.cpp compares them).
#ifndef NIMBUS_TONEMAP_GLSL
#define NIMBUS_TONEMAP_GLSL
vec3 aces_fitted(vec3 c) {
  // GLSL matrices are column-major: these are the transposes of the C++ row tables.
  const mat3 to_rrt = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777);
  const mat3 from_odt = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602);
  vec3 v = to_rrt * c;
  v = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
  return clamp(from_odt * v, 0.0, 1.0);
}

// AgX (render/image/src/image_png.cpp, agx(): the same figures and steps). GLSL matrices are
// column-major, so each is written as the transpose of its C++ table.
vec3 agx(vec3 c) {
  const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                          0.0784335999999992, 0.878468636469772, 0.0784336,
                          0.0792237451477643, 0.0791661274605434, 0.879142973793104);
  const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                           -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                           -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
  const float min_ev = -12.47393, max_ev = 4.026069;
  // Rows divided by their sums (M 1), so a grey stays grey.
  vec3 t = (clamp(log2(max(inset * c / (inset * vec3(1.0)), vec3(1.0e-10))), min_ev, max_ev) - min_ev) / (max_ev - min_ev);
  vec3 t2 = t * t, t4 = t2 * t2;
  vec3 v = 15.5 * t4 * t2 - 40.14 * t4 * t + 31.96 * t4 - 6.868 * t2 * t + 0.4298 * t2 + 0.1191 * t - 0.00232;
  return pow(clamp(outset * v / (outset * vec3(1.0)), 0.0, 1.0), vec3(2.2));
}

vec3 srgb_encode(vec3 linear) {
  vec3 x = clamp(linear, 0.0, 1.0);
  return mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), x));
}
#endif

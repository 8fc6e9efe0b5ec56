// Display encoding shared by the viewer's screen and its PNG screenshots: Stephen Hill's fit of
// the ACES RRT + sRGB ODT (BakingLab ACES.hlsl, 2016) and the sRGB transfer curve (IEC 61966-2-1).
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

vec3 srgb_encode(vec3 linear) {
  vec3 x = clamp(linear, 0.0, 1.0);
  return mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), x));
}
#endif

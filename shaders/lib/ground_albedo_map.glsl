// Where the ground's albedo texture (render/scene/ground_albedo.hpp) is read for one pixel: the
// pixel's footprint on the ground, the taps that cover it and their mip level, and how the two
// scales combine. Common subset of GLSL 4.50 and C++ (glm): render/scene/src/ground_albedo.cpp
// compiles this file too, so the CPU reference and the surface pass read the same texels.
#ifndef NIMBUS_GROUND_ALBEDO_MAP_GLSL
#define NIMBUS_GROUND_ALBEDO_MAP_GLSL

const int GROUND_TAPS = 4;                   // taps along the footprint's long axis
const float GROUND_MIN_GRAZING = 1.0e-4f;    // |dir.y| floor: the long axis stays finite at the horizon
const float GROUND_DETAIL_CONTRAST = 0.5f;   // the detail's brightness is 1 + this (lum / mean - 1)

// The footprint of a pixel (a cone of angle a) on a horizontal plane, seen along unit dir at
// distance d: an ellipse with short axis d a (across the view) and long axis d a / |dir.y| (along
// the view's horizontal direction), to first order in a (the elliptical footprint of Heckbert 1989).
// Returns (short, long) in metres.
vec2 ground_footprint(float dir_y, float distance_m, float pixel_angle_rad) {
  float across = distance_m * pixel_angle_rad;
  return vec2(across, across / max(abs(dir_y), GROUND_MIN_GRAZING));
}

// Each of the GROUND_TAPS taps covers max(short, long / GROUND_TAPS) metres: the mip level
// for a texture of texel_m metres (negative: the magnified level 0).
float ground_lod(vec2 footprint_m, float texel_m) {
  float w = max(footprint_m.x, footprint_m.y / float(GROUND_TAPS));
  return log2(max(w / texel_m, 1.0e-6f));
}

// Tap k's offset along the long axis, metres: the centres of GROUND_TAPS equal parts of it.
float ground_tap_offset(int k, float long_m) {
  return ((float(k) + 0.5f) / float(GROUND_TAPS) - 0.5f) * long_m;
}

// The albedo from the land use (one RGB read at the long period) and the detail (a read of the
// same texture at the short period, its luminance against the texture's mean), clamped to [0, 1].
vec3 ground_combine(vec3 land, vec3 detail, float mean_luminance) {
  float lum = 0.2126f * detail.x + 0.7152f * detail.y + 0.0722f * detail.z;
  float b = 1.0f + GROUND_DETAIL_CONTRAST * (lum / mean_luminance - 1.0f);
  return clamp(land * b, vec3(0.0f), vec3(1.0f));
}

#endif

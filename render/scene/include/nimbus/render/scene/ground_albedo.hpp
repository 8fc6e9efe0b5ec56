// The sky scene's ground albedo: fields, meadows, woods and bare soil seen from a few hundred
// metres up, as a Lambert albedo that varies over the ground. It is one periodic RGB texture
// baked on the CPU from the noise module (periodic gradient fBm, so it tiles seamlessly), with
// its mip chain, read at two scales: the land-use pattern (a period of kilometres) times a
// brightness detail (the same texture at a shorter, incommensurate period: metres to tens of
// metres). Each read is filtered by the pixel's footprint on the ground (a few taps along the
// footprint's long axis at the mip level of its short one, shaders/lib/ground_albedo_map.glsl),
// so the ground does not shimmer toward the horizon. The GPU surface pass
// (shaders/lib/ground_albedo.glsl) and the CPU reference read the same texels through the same
// map, so they agree.
//
// The albedos: broadband surface albedos in Oke (1987, Boundary Layer Climates, table 2.1):
// grass 0.16-0.26, crops 0.18-0.25, deciduous forest 0.15-0.20, coniferous forest 0.05-0.15,
// soils 0.05-0.40. Their visible-band tints (green vegetation, brown soil) are chosen here; the
// luminances (Rec. 709 weights) lie in those ranges (docs/references.md).
#pragma once
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace nimbus::render {

struct GroundAlbedoParams {
  int size = 512;                 // texels per side of level 0, a power of two in [16, 4096]
  double period_m = 6144.0;       // metres over which the land-use pattern repeats
  double detail_period_m = 829.0; // metres over which the brightness detail repeats (period_m / 7.41: no common period nearby)
  double detail_strength = 0.35;  // the detail's brightness factor spans 1 -/+ this (at most; fBm rarely reaches it)
  unsigned seed = 11;
  bool operator==(const GroundAlbedoParams&) const = default;
};

// The baked texture: level 0 is size x size texels over one period (texel (i, j) centred at
// ((i + 1/2) / size, (j + 1/2) / size) of it, x fastest, then z), each further level the 2 x 2 box
// mean of the one before, down to 1 x 1. Linear albedo per channel, in [0, 1].
struct GroundAlbedoTexture {
  GroundAlbedoParams params;
  std::vector<std::vector<glm::vec3>> levels;
  glm::dvec3 mean{0.0};          // mean albedo of level 0 (= the 1 x 1 level, up to float rounding)
  double mean_luminance = 0.0;   // its Rec. 709 luminance: the detail's brightness divides by it
  int size(int level) const { return params.size >> level; }
  int level_count() const { return static_cast<int>(levels.size()); }
};

// Bakes the texture (noise module, TBB). Throws std::invalid_argument naming the bad parameter.
// The sky scene's is built once per process and shared (sky_ground_albedo()).
std::shared_ptr<const GroundAlbedoTexture> bake_ground_albedo(const GroundAlbedoParams& params);
std::shared_ptr<const GroundAlbedoTexture> sky_ground_albedo();

// Trilinear read of the texture (repeating) at texture coordinate uv (periods), level lod
// (clamped to the chain), as the GPU's GL_LINEAR_MIPMAP_LINEAR with GL_REPEAT reads it.
glm::dvec3 sample_ground_texture(const GroundAlbedoTexture& t, glm::dvec2 uv, double lod);

// The ground's albedo at world (x, z) metres for a pixel seen along unit view direction `dir`
// at distance `distance_m` by a camera whose pixel subtends `pixel_angle_rad`: the land use
// times the detail's brightness, each filtered over the pixel's footprint on the ground, clamped
// to [0, 1]. shaders/lib/ground_albedo.glsl is the same function on the GPU.
glm::dvec3 ground_albedo(const GroundAlbedoTexture& t, double x_m, double z_m, const glm::dvec3& dir,
                         double distance_m, double pixel_angle_rad);

}  // namespace nimbus::render

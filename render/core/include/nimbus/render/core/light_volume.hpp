// The per-voxel light volume (seed 004, "Helligkeitsberechnung an den Gitterpunkten": brightness
// computed at grid points, then read while slicing): on a coarse grid of cells over the clouds'
// box, the fluence phi and the net flux F of the sunlight that has scattered at least once, per
// unit sun irradiance. The slicer adds the radiance it in-scatters toward the eye to its exact
// single scattering, in the P1 (diffusion) approximation of the radiance (Jensen et al. 2001,
// eq. 3): L(w) ~ (phi + 3 F.w) / (4 pi), so that with a phase of mean cosine g
//   int p(w_i . w_o) L(w_i) dw_i = (phi + 3 g F.w_o) / (4 pi)              (docs/clouds.md, eq. MS-1)
// (the first Legendre moment of Henyey-Greenstein is g), clamped at 0. Built on the CPU by the
// photon tracer of render/reference (light_volume_builder.hpp); plain data here.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/cloud_optics.hpp"

namespace nimbus::render {

struct LightVolume {
  int size[3] = {0, 0, 0};        // cells per axis
  glm::dvec3 world_min{0.0};      // the grid's corner, metres
  double cell_m = 0.0;            // cube cells, metres per side
  // Per cell, x fastest: fluence of once-or-more scattered light per unit irradiance, RGB
  // (dimensionless: W m^-2 per W m^-2), and the net flux per unit irradiance (xyz, world axes,
  // the channels' mean).
  std::vector<float> fluence_rgb;
  std::vector<float> flux_xyz;
  // How it was made, for metadata and the bench.
  std::int64_t photons = 0;
  std::uint64_t seed = 0;
  double build_seconds = 0.0;

  std::size_t cells() const { return static_cast<std::size_t>(size[0]) * size[1] * size[2]; }
  glm::dvec3 world_max() const { return world_min + cell_m * glm::dvec3(size[0], size[1], size[2]); }
};

// The cells' trilinear interpolation at a world point, cell values at cell centres, clamped to
// the edge cells outside (as the GL texture with GL_CLAMP_TO_EDGE samples it).
// fluence: RGB; flux: xyz.
void sample_light_volume(const LightVolume& volume, const glm::dvec3& world_m, glm::dvec3& fluence, glm::dvec3& flux);

// Mean cosine of the dual-lobe phase: w g_forward + (1 - w) g_back.
double mean_cosine(const DualLobePhase& phase);

// Eq. MS-1 per unit irradiance, RGB: the radiance that the light volume's scattered light
// in-scatters at `world_m` toward the eye, per unit scattering coefficient, where `to_eye` is the
// unit direction of propagation toward the eye; the flux term scaled per channel by
// fluence_c / mean(fluence); each channel clamped at 0.
glm::dvec3 light_volume_inscatter(const LightVolume& volume, const DualLobePhase& phase, const glm::dvec3& world_m,
                                  const glm::dvec3& to_eye);

}  // namespace nimbus::render

// The per-voxel light volume (Hoffmann 2007, "Helligkeitsberechnung an den Gitterpunkten": brightness
// computed at grid points, then read while slicing): on a coarse grid of cells over the clouds'
// box, the fluence phi and the net flux F of the sunlight that has scattered at least once, per
// unit sun irradiance, and the traceless second moment Q = int L(w) (w w^T - I / 3) dw. The slicer
// adds the radiance it in-scatters toward the eye to its exact single scattering, with the
// radiance cut after its l = 2 spherical harmonics (l <= 1 is the P1 or diffusion form, Jensen et
// al. 2001, eq. 3): L(w) ~ phi / (4 pi) + 3 F.w / (4 pi) + 15 w^T Q w / (8 pi), so that with a
// phase whose Legendre coefficients are p_1 = g and p_2 (Henyey-Greenstein: g^l)
//   int p(w_i . w_o) L(w_i) dw_i = phi / (4 pi) + 3 g F.w_o / (4 pi) + 15 p_2 w_o^T Q w_o / (8 pi)
//                                                                         (docs/clouds.md, eq. MS-1)
// clamped at 0.
//
// The light of the first scattering orders is too peaked for l <= 2 (with HG 0.7, double
// scattering seen 47 degrees off the sun is 27 % too bright cut there). Orders k = 1, 2 are kept
// apart as lobes: a fraction f_k of the fluence, modelled as L_k(w) = f_k phi HG(mu_k; w.s) about
// the sun's direction of propagation s, with mu_k their measured mean cosine to s. Henyey-
// Greenstein lobes convolve exactly (Legendre coefficients multiply: HG(a) * HG(b) = HG(ab)), so
// they in-scatter f_k phi sum_i w_i HG(g_i mu_k; w_o.s); the harmonics carry the rest, their
// l <= 2 moments less the lobes' own (phi f_k, phi f_k mu_k s, phi f_k mu_k^2 (s s^T - I / 3)):
//                                                                         (docs/clouds.md, eq. MS-3)
// so the volume's fluence, flux and Q stay those of all the scattered light.
//
// A cell's mean fluence placed at its centre cannot show how the fluence falls toward a cloud's
// edge within it, and the eye sees little more than the first mean free path (200 m cells on a
// 400 m stratus sheet seen from below: 64 % too bright). Each cell also holds a linear fit of the
// fluence over its part of the cloud, phi(u) = phi_c + g_c . (u - ubar_c) (u in cells from the
// grid's corner, ubar_c the centroid of what the cloud's bricks cover in it). Read between cells
// as the trilinear weights w_c of their fits (exact for a linear field, continuous):
//   phi(u) = sum_c w_c phi_c + (sum_c w_c g_c) . u - sum_c w_c (g_c . ubar_c)      (eq. MS-4)
// which the GL texture's own filtering evaluates from (phi, g, h = g . ubar) per cell; the
// in-scattering of eqs. MS-1 and MS-3 is scaled by phi(u) / sum_c w_c phi_c (>= 0). Built on the CPU by
// the photon tracer of render/reference (light_volume_builder.hpp); plain data here.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/cloud_optics.hpp"

namespace nimbus::render {

struct LightVolume {
  int size[3] = {0, 0, 0};        // cells per axis
  glm::dvec3 world_min{0.0};      // the grid's corner, metres
  glm::dvec3 cell_m{0.0};         // a cell's sides, metres per axis (the builder makes cubes)
  // Per cell, x fastest: fluence of once-or-more scattered light per unit irradiance, RGB
  // (dimensionless: W m^-2 per W m^-2), and the net flux per unit irradiance (xyz, world axes,
  // the channels' mean).
  std::vector<float> fluence_rgb;
  std::vector<float> flux_xyz;
  // Per cell: Q per unit irradiance (the channels' mean): xx, yy, xy, xz, yz (zz = -xx - yy).
  std::vector<float> quadrupole;
  // Per cell: the lobes of scattering orders 1 and 2 (eq. MS-3): f_1, mu_1, f_2, mu_2, with
  // f_k in [0, 1] (f_1 + f_2 <= 1) and mu_k in [-0.95, 0.95]. Empty, or f_k = 0: no lobes.
  std::vector<float> lobes;
  // Per cell: eq. MS-4's fit, the mean fluence's gradient in cells (d phi / d u, xyz; the
  // channels' mean) and h = g . ubar. Empty: none (phi constant about each centre).
  std::vector<float> gradient;
  // The sun's direction of propagation (unit; the lobes' axis).
  glm::dvec3 light_direction{0.0, -1.0, 0.0};
  // How it was made, for metadata and the bench.
  std::int64_t photons = 0;
  std::uint64_t seed = 0;
  int lobe_orders = 0;  // orders kept as lobes (LightVolumeSettings::lobe_orders)
  double diffusion_depth = 0.0;  // LightVolumeSettings::diffusion_depth (0: photons carried all the light)
  double similarity_depth = 0.0;  // LightVolumeSettings::similarity_depth (0: the true phase everywhere)
  int diffusion_iterations = 0;  // the diffusion solve's conjugate-gradient iterations (0: none)
  double build_seconds = 0.0;

  std::size_t cells() const { return static_cast<std::size_t>(size[0]) * size[1] * size[2]; }
  glm::dvec3 world_max() const { return world_min + cell_m * glm::dvec3(size[0], size[1], size[2]); }
};

struct LightVolumeSample {
  glm::dvec3 fluence{0.0};  // RGB
  glm::dvec3 flux{0.0};     // xyz
  glm::dmat3 quadrupole{0.0};  // symmetric, traceless
  glm::dvec4 lobes{0.0};       // f_1, mu_1, f_2, mu_2
  double fit_offset = 0.0;     // eq. MS-4: sum w_c g_c . u - sum w_c h_c, to add to the mean fluence
};

// Whether the volume's arrays match its size (lobes and fits may be empty), its cells are
// positive and every value is finite: what mixing and uploading a volume require.
bool light_volume_is_consistent(const LightVolume& volume);

// The cells' trilinear interpolation at a world point, cell values at cell centres, clamped to
// the edge cells outside (as the GL texture with GL_CLAMP_TO_EDGE samples it).
LightVolumeSample sample_light_volume(const LightVolume& volume, const glm::dvec3& world_m);

// (1 - t) a + t b on a's grid, b read at a's cell centres by sample_light_volume (so b may lie
// on another grid: the volumes of two keyframes of an evolving sky, each built over its own box).
// t in [0, 1]; both volumes non-empty, else std::invalid_argument naming which. The animated sky
// draws keyframe k's volume blended towards k + 1's as its density blends (sky_renderer.hpp).
LightVolume mix_light_volumes(const LightVolume& a, const LightVolume& b, double t);

// Legendre coefficients of a phase of Henyey-Greenstein lobes (p_0 = 1), in its dual-lobe form
// (as_dual_lobes): p_l = w g^l + (1 - w) g_back^l.
double phase_legendre(const Phase& phase, int l);

// Eqs. MS-1, MS-3 and MS-4 per unit irradiance, RGB: the radiance that the light volume's scattered light
// in-scatters at `world_m` toward the eye, per unit scattering coefficient, where `to_eye` is the
// unit direction of propagation toward the eye; the flux and quadrupole terms scaled per channel
// by fluence_c / mean(fluence), as the lobes; the harmonics' part of each channel clamped at 0.
glm::dvec3 light_volume_inscatter(const LightVolume& volume, const Phase& phase, const glm::dvec3& world_m,
                                  const glm::dvec3& to_eye);

}  // namespace nimbus::render

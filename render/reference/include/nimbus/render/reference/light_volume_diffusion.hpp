// The light deep inside the clouds as diffusion on the light volume's grid (docs/clouds.md, "Deep
// light diffused"). Photons carry the light near the clouds' surfaces, what the eye sees; where a
// photon scatters in a cell deep inside (transport optical depth to vacuum of at least
// LightVolumeSettings::diffusion_depth) its weight becomes a source q, and all the light it would
// have carried on is the solution of the diffusion equation (Stam 1995)
// with Marshak's vacuum condition on the faces to empty cells (Duderstadt & Hamilton 1976):
//   -div(D grad phi) + sigma_a phi = q,  D = 1 / (3 sigma_tr),  sigma_tr = sigma_t - sigma_s g  (eq. MS-5)
//   at a face to vacuum: the incoming partial current phi / 4 - J / 2 = 0, so J = phi_face / 2
// discretised by finite volumes (cell-mean sigma_t, sigma_s and g) and solved by conjugate
// gradients. Light scattered that often has forgotten its direction (diffusion is its l <= 1
// form), so its net flux is F = -D grad phi and its second moment 0.
#pragma once
#include <glm/glm.hpp>

#include <stop_token>
#include <vector>

#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/core/light_volume.hpp"
#include "nimbus/render/reference/light_volume_stages.hpp"

namespace nimbus::render::light_volume {

// Each cell's mean optics over its whole volume: extinction and scattering per metre (per channel)
// and the phase's mean cosine g (scattering-weighted over the clouds). A cell with sigma_t = 0 is
// vacuum for the solve.
struct CellMedium {
  std::vector<double> sigma_t;        // per metre
  std::vector<glm::dvec3> sigma_s;    // per metre, RGB
  std::vector<double> mean_cosine;    // g
};

// The cells' mean optics, from the clouds' densities at 2^3 stratified points per cell.
CellMedium cell_medium(const LightVolume& grid, const CellGrid& g, const std::vector<CloudVolume>& clouds);

// Per cell, 1 where its centre lies at least `depth` transport mean free paths (optical depth in
// sigma_tr = sigma_t - sigma_s g, the channels' mean) from vacuum along the grid's faces: the
// shortest path from the cell's centre through face-adjacent cells to a vacuum cell's face or the
// grid's edge.
std::vector<char> cells_deeper_than(const CellGrid& g, const glm::dvec3& cell_m, const CellMedium& medium, double depth);

// The diffusion solution on the grid (eq. MS-5), per channel: phi (fluence, per unit irradiance
// when q is per unit irradiance) and the net flux through each cell (the mean of its faces'
// currents, world axes, per channel).
struct DiffusedLight {
  std::vector<glm::dvec3> fluence;     // RGB per cell
  std::vector<glm::dvec3> flux[3];     // per channel: xyz per cell
  std::vector<glm::dvec3> gradient;    // the channels' mean fluence's gradient, per cell (d phi / d u, u in cells)
  int iterations = 0;                  // conjugate-gradient iterations, the most of the channels
  double residual = 0.0;               // relative residual reached, the worst of the channels
};

// Solves eq. MS-5 with source q (RGB per cell, W m^-3 per unit irradiance) on cells of side
// cell_m. Cells with sigma_t = 0 are vacuum, and so is everything past the grid's faces.
// Converges to a relative residual of `tolerance` (at most `max_iterations`); throws Cancelled
// between iterations once `stop` is requested (nimbus/base/cancel.hpp).
DiffusedLight solve_diffusion(const CellGrid& g, const glm::dvec3& cell_m, const CellMedium& medium,
                              const std::vector<glm::dvec3>& q, double tolerance = 1e-6, int max_iterations = 4000,
                              const std::stop_token& stop = {});

}  // namespace nimbus::render::light_volume

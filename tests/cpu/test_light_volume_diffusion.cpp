// The light volume's diffused orders (render/reference light_volume_diffusion.hpp, eq. MS-5): the
// finite-volume solve against the closed-form solution of a homogeneous slab with Marshak's
// vacuum condition; energy conserved (what the sources emit is absorbed or leaves through the
// vacuum faces); no negative or non-finite fluence on a rough medium with holes; and the cells'
// mean optics of a homogeneous cloud.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "nimbus/render/reference/light_volume_diffusion.hpp"
#include "slab_volume.hpp"

namespace nimbus::render::light_volume {
namespace {

CellMedium uniform_medium(const CellGrid& g, double sigma_t, double albedo, double mean_cosine) {
  CellMedium m;
  m.sigma_t.assign(g.cells(), sigma_t);
  m.sigma_s.assign(g.cells(), glm::dvec3(sigma_t * albedo));
  m.mean_cosine.assign(g.cells(), mean_cosine);
  return m;
}

// -D phi'' + sigma_a phi = q on [0, H] with phi -+ 2 D phi' = 0 at the faces (Marshak): the
// solution phi = q / sigma_a (1 - A cosh((y - H / 2) / L)), L = sqrt(D / sigma_a),
// A = 1 / (cosh(H / 2L) + (2D / L) sinh(H / 2L)).
double slab_fluence(double y, double H, double D, double sigma_a, double q) {
  const double L = std::sqrt(D / sigma_a);
  const double A = 1.0 / (std::cosh(H / (2.0 * L)) + 2.0 * D / L * std::sinh(H / (2.0 * L)));
  return q / sigma_a * (1.0 - A * std::cosh((y - H / 2.0) / L));
}

// A slab 10 m thick (40 cells of 0.25 m) and 30 m wide: sigma_t 1 per m, albedo 0.7, g 0.5
// (D = 1 / (3 (1 - 0.35)) = 0.51 m, L = sqrt(D / sigma_a) = 1.3 m), a uniform source. The central
// column against the closed form: measured worst 0.25 % (second-order finite volumes; the sides
// 11 L away); tolerance 1 %. Its net
// flux leaves through both faces: the mean of a face cell's two face currents, measured within
// 0.3 % of the closed form's -D dphi/dy at its centre; tolerance 3 %.
TEST(LightVolumeDiffusion, HomogeneousSlabMatchesTheClosedForm) {
  const CellGrid g{120, 40, 120};
  const glm::dvec3 h(0.25);
  const double sigma_t = 1.0, albedo = 0.7, mean_cosine = 0.5, q0 = 2.0;
  const CellMedium m = uniform_medium(g, sigma_t, albedo, mean_cosine);
  const std::vector<glm::dvec3> q(g.cells(), glm::dvec3(q0));
  const DiffusedLight light = solve_diffusion(g, h, m, q, 1e-9);
  std::printf("slab: %d iterations, residual %.2e\n", light.iterations, light.residual);
  EXPECT_LT(light.residual, 1e-9);
  const double D = 1.0 / (3.0 * (sigma_t - sigma_t * albedo * mean_cosine)), sigma_a = sigma_t * (1.0 - albedo);
  const double H = g.ny * h.y;
  double worst = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    const std::size_t c = g.index(g.nx / 2, j, g.nz / 2);
    const double y = (j + 0.5) * h.y;
    const double expected = slab_fluence(y, H, D, sigma_a, q0);
    worst = std::max(worst, std::abs(light.fluence[c].x / expected - 1.0));
    EXPECT_NEAR(light.fluence[c].x, expected, 0.01 * expected) << "cell " << j;
    EXPECT_EQ(light.fluence[c].x, light.fluence[c].z);  // grey: one solution for every channel
  }
  std::printf("slab: worst %.3f %% off the closed form\n", 100.0 * worst);
  for (int j : {0, g.ny - 1}) {
    const std::size_t c = g.index(g.nx / 2, j, g.nz / 2);
    const double y = (j + 0.5) * h.y, dy = 1e-4;
    const double flux = -D * (slab_fluence(y + dy, H, D, sigma_a, q0) - slab_fluence(y - dy, H, D, sigma_a, q0)) / (2 * dy);
    std::printf("slab: cell %d flux %.5f (closed form %.5f)\n", j, light.flux[0][c].y, flux);
    EXPECT_NEAR(light.flux[0][c].y, flux, 0.03 * std::abs(flux)) << "cell " << j;
    EXPECT_NEAR(light.flux[0][c].x, 0.0, 1e-6 * std::abs(flux));
  }
}

// A rough medium with holes (a third of the cells vacuum, extinction over three decades,
// chromatic albedo) and a random source: in each channel, the power the sources emit equals what
// is absorbed plus what leaves through the faces to vacuum (Marshak's current phi / (h / 2D + 2)),
// to the solver's tolerance; the fluence finite and >= 0, 0 in vacuum.
TEST(LightVolumeDiffusion, ConservesEnergyOnARoughMediumWithHoles) {
  const CellGrid g{18, 12, 15};
  const glm::dvec3 h(2.0, 1.5, 1.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  CellMedium m;
  std::vector<glm::dvec3> q(g.cells());
  const glm::dvec3 albedo(0.99, 0.95, 0.8);
  for (std::size_t c = 0; c < g.cells(); ++c) {
    const bool vacuum = u(rng) < 0.33;
    const double sigma_t = vacuum ? 0.0 : 0.5 * std::pow(10.0, 3.0 * u(rng) - 1.0);  // 0.05 .. 50 per m
    m.sigma_t.push_back(sigma_t);
    m.sigma_s.push_back(sigma_t * albedo);
    m.mean_cosine.push_back(0.8 * u(rng));
    q[c] = vacuum ? glm::dvec3(0.0) : glm::dvec3(u(rng), u(rng), u(rng));
  }
  const DiffusedLight light = solve_diffusion(g, h, m, q, 1e-10);
  EXPECT_LT(light.residual, 1e-10);
  const double hmax = std::max({h.x, h.y, h.z}), V = h.x * h.y * h.z;
  for (int ch = 0; ch < 3; ++ch) {
    double emitted = 0.0, absorbed = 0.0, leaked = 0.0;
    g.for_each_cell([&](int i, int j, int k, std::size_t c) {
      const double phi = light.fluence[c][ch];
      EXPECT_TRUE(std::isfinite(phi) && phi >= 0.0);
      if (m.sigma_t[c] == 0.0) {
        EXPECT_EQ(phi, 0.0);
        return;
      }
      emitted += q[c][ch] * V;
      absorbed += (m.sigma_t[c] - m.sigma_s[c][ch]) * phi * V;
      const double D = 1.0 / (3.0 * std::max(m.sigma_t[c] - m.sigma_s[c][ch] * m.mean_cosine[c], 1.0 / (300.0 * hmax)));
      const int at[3] = {i, j, k}, size[3] = {g.nx, g.ny, g.nz};
      for (int f = 0; f < 6; ++f) {
        int nb[3] = {at[0], at[1], at[2]};
        nb[f / 2] += (f & 1) ? 1 : -1;
        const bool outside = nb[f / 2] < 0 || nb[f / 2] >= size[f / 2];
        if (!outside && m.sigma_t[g.index(nb[0], nb[1], nb[2])] > 0.0) continue;
        const double area = V / h[f / 2];
        leaked += area * phi / (h[f / 2] / (2.0 * D) + 2.0);
      }
    });
    std::printf("channel %d: emitted %.6f, absorbed %.6f, leaked %.6f\n", ch, emitted, absorbed, leaked);
    EXPECT_NEAR(absorbed + leaked, emitted, 1e-6 * emitted) << "channel " << ch;
    EXPECT_GT(leaked, 0.0);
  }
}

// A homogeneous cloud's cells inside it read its own optics; cells outside its support read vacuum.
TEST(LightVolumeDiffusion, CellMediumOfAHomogeneousCloudIsItsOptics) {
  const Phase phase = dual_lobe_phase(0.7, -0.2, 0.75);
  const CloudVolume cloud = test::slab(8.0, 16, 16, phase, 0.97);  // 16 x 16 x 16 voxels of 1 m
  LightVolume grid;
  grid.world_min = glm::dvec3(-4.0);
  grid.cell_m = glm::dvec3(2.0);
  const CellGrid g{12, 12, 12};
  grid.size[0] = grid.size[1] = grid.size[2] = 12;
  const CellMedium m = cell_medium(grid, g, {cloud});
  const double g_mean = 0.75 * 0.7 + 0.25 * -0.2;
  int inside = 0;
  g.for_each_cell([&](int i, int j, int k, std::size_t c) {
    const glm::dvec3 lo = grid.world_min + grid.cell_m * glm::dvec3(i, j, k), hi = lo + grid.cell_m;
    if (glm::all(glm::greaterThanEqual(lo, glm::dvec3(0.0))) && glm::all(glm::lessThanEqual(hi, glm::dvec3(15.0)))) {
      ++inside;
      EXPECT_NEAR(m.sigma_t[c], 0.5, 1e-9);
      EXPECT_NEAR(m.sigma_s[c].y, 0.5 * 0.97, 1e-9);
      EXPECT_NEAR(m.mean_cosine[c], g_mean, 1e-9);
    }
    if (glm::any(glm::lessThan(hi, glm::dvec3(-1.0))) || glm::any(glm::greaterThan(lo, glm::dvec3(16.0)))) {
      EXPECT_EQ(m.sigma_t[c], 0.0);
    }
  });
  EXPECT_GT(inside, 100);
}

}  // namespace
}  // namespace nimbus::render::light_volume

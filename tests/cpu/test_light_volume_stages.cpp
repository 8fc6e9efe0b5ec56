// The light volume's stages after the photons (nimbus/render/reference/light_volume_stages.hpp),
// each on a small hand-made grid: the launch rectangle covers the box from upstream, the cell
// values are track length per covered volume (pooled where barely covered), the spike clamp
// bounds a lone bright cell, the smoothing keeps |F| <= phi, the fits recover a linear field,
// the empty rings fill from their neighbours, and the packing's lobes stay in range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "nimbus/render/reference/light_volume_stages.hpp"

namespace nimbus::render::light_volume {
namespace {

// A grid of n^3 cells with every value of every known cell set by f(cell, channel).
template <class F>
CellValues uniform_values(const CellGrid& g, F f) {
  CellValues v;
  v.value.assign(g.cells() * kTallies, 0.0f);
  v.known.assign(g.cells(), 1);
  for (std::size_t q = 0; q < g.cells(); ++q)
    for (int c = 0; c < kTallies; ++c) v.value[q * kTallies + c] = f(q, c);
  return v;
}

double fluence(const CellValues& v, std::size_t q) {
  return (v.value[q * kTallies] + v.value[q * kTallies + 1] + v.value[q * kTallies + 2]) / 3.0;
}

TEST(LightVolumeStages, TheLaunchRectangleCoversTheBoxFromUpstream) {
  LightVolume grid;
  grid.world_min = {-3.0, 1.0, 2.0};
  grid.size[0] = 10;
  grid.size[1] = 4;
  grid.size[2] = 6;
  grid.cell_m = glm::dvec3(0.5, 2.0, 1.0);
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  std::vector<glm::dvec3> directions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {1, 1e-12, 0},
                                        {0.9, 0.436, 0}};
  for (int i = 0; i < 50; ++i) directions.push_back({n01(rng), n01(rng), n01(rng)});
  for (const glm::dvec3& to_light : directions) {
    const LaunchRect r = launch_rect(grid, to_light);
    EXPECT_NEAR(glm::length(r.l), 1.0, 1e-12);
    EXPECT_NEAR(glm::length(r.eu), 1.0, 1e-12);
    EXPECT_NEAR(glm::length(r.ev), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(r.l, r.eu), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(r.l, r.ev), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(r.eu, r.ev), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(r.l, glm::normalize(to_light)), -1.0, 1e-12);  // the light propagates away from the sun
    const glm::dvec3 hi = grid.world_max();
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 p((c & 1) ? hi.x : grid.world_min.x, (c & 2) ? hi.y : grid.world_min.y,
                         (c & 4) ? hi.z : grid.world_min.z);
      EXPECT_GE(glm::dot(p, r.eu), r.umin - 1e-9);
      EXPECT_LE(glm::dot(p, r.eu), r.umax + 1e-9);
      EXPECT_GE(glm::dot(p, r.ev), r.vmin - 1e-9);
      EXPECT_LE(glm::dot(p, r.ev), r.vmax + 1e-9);
      EXPECT_GE(glm::dot(p, r.l), r.lmin - 1e-9);
    }
    // The rectangle holds the box's shadow (at least its smallest face: the shadow's area is
    // sum |l_i| A_i with sum |l_i| >= 1), and each side is at most the box's diagonal.
    const glm::dvec3 e = hi - grid.world_min;
    EXPECT_GE(r.area_m2(), std::min({e.x * e.y, e.y * e.z, e.x * e.z}) * (1.0 - 1e-9));
    EXPECT_LE(r.area_m2(), glm::dot(e, e) * (1.0 + 1e-9));
    // Origins sit on the rectangle, upstream of the box.
    const glm::dvec3 o = r.origin(0.25, 0.75, 1.0);
    EXPECT_NEAR(glm::dot(o, r.l), r.lmin - 1.0, 1e-9);
    EXPECT_NEAR(glm::dot(o, r.eu), r.umin + 0.25 * (r.umax - r.umin), 1e-9);
  }
}

TEST(LightVolumeStages, CellValuesAreTrackPerCoveredVolumeAndPoolWhereBarelyCovered) {
  const CellGrid g{3, 3, 3};
  std::vector<std::int64_t> tally(g.cells() * kTallies);
  std::vector<double> covered(g.cells(), 1.0);
  for (std::size_t q = 0; q < g.cells(); ++q)
    for (int c = 0; c < kTallies; ++c) tally[q * kTallies + c] = std::int64_t(100 + q + c);
  const std::size_t centre = g.index(1, 1, 1), corner = g.index(0, 0, 0), half = g.index(2, 1, 1);
  covered[centre] = 0.25;  // barely covered: pools its 27 cells
  covered[corner] = 0.0;   // no cloud
  covered[half] = 0.5;     // at the threshold: its own tallies over its fraction
  const double scale = 0.01;
  const CellValues v = cell_values(g, tally, covered, scale);
  EXPECT_EQ(v.known[corner], 0);
  for (int c = 0; c < kTallies; ++c) EXPECT_EQ(v.value[corner * kTallies + c], 0.0f);
  EXPECT_EQ(v.known[half], 1);
  EXPECT_FLOAT_EQ(v.value[half * kTallies + 4], float(scale * double(100 + half + 4) / 0.5));
  const std::size_t full = g.index(1, 0, 2);
  EXPECT_FLOAT_EQ(v.value[full * kTallies + 0], float(scale * double(100 + full)));
  // The pooled cell: the ratio of the neighbourhood's sums.
  double area = 0.0, sum = 0.0;
  for (std::size_t q = 0; q < g.cells(); ++q) {
    area += covered[q];
    sum += double(100 + q + 7);
  }
  EXPECT_FLOAT_EQ(v.value[centre * kTallies + 7], float(scale * sum / area));
}

TEST(LightVolumeStages, ALoneSpikeIsClampedToTwiceItsNeighboursKeepingItsAnisotropy) {
  const CellGrid g{3, 3, 3};
  CellValues v = uniform_values(g, [](std::size_t, int c) { return c < 3 ? 1.0f : 0.1f * float(c % 5); });
  const std::size_t centre = g.index(1, 1, 1), edge = g.index(0, 1, 1);
  for (int c = 0; c < kTallies; ++c) v.value[centre * kTallies + c] *= 10.0f;
  // A cell at 1.5x its neighbours is left alone; a cell with under 6 known neighbours too.
  const CellValues before = v;
  CellValues mild = uniform_values(g, [](std::size_t, int) { return 1.0f; });
  for (int c = 0; c < kTallies; ++c) mild.value[centre * kTallies + c] = 1.5f;
  const CellValues mild_before = mild;
  clamp_spikes(g, v);
  clamp_spikes(g, mild);
  EXPECT_NEAR(fluence(v, centre), kSpike * 1.0, 1e-6);
  for (int c = 3; c < kTallies; ++c)  // every channel scaled by the same factor
    EXPECT_NEAR(v.value[centre * kTallies + c], before.value[centre * kTallies + c] * 0.2, 1e-6);
  EXPECT_EQ(v.value[edge * kTallies], before.value[edge * kTallies]);
  EXPECT_EQ(mild.value, mild_before.value);
  CellValues sparse = uniform_values(g, [](std::size_t, int) { return 1.0f; });
  for (std::size_t q = 0; q < g.cells(); ++q) sparse.known[q] = q == centre || q == edge;
  for (int c = 0; c < kTallies; ++c) sparse.value[centre * kTallies + c] = 50.0f;
  const CellValues sparse_before = sparse;
  clamp_spikes(g, sparse);
  EXPECT_EQ(sparse.value, sparse_before.value);
}

TEST(LightVolumeStages, SmoothingTheAnisotropyKeepsTheFluenceAndTheBoundOnTheFlux) {
  const CellGrid g{4, 3, 5};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  CellValues v = uniform_values(g, [](std::size_t, int) { return 0.0f; });
  for (std::size_t q = 0; q < g.cells(); ++q) {
    const float phi = 0.1f + u(rng);
    for (int c = 0; c < 3; ++c) v.value[q * kTallies + c] = phi;
    glm::vec3 f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
    f = glm::normalize(f) * phi * u(rng);  // |F| <= phi
    for (int c = 0; c < 3; ++c) v.value[q * kTallies + 3 + c] = f[c];
    v.known[q] = q % 7 != 3;
  }
  const CellValues before = v;
  smooth_anisotropy(g, v);
  for (std::size_t q = 0; q < g.cells(); ++q) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(v.value[q * kTallies + c], before.value[q * kTallies + c]);
    if (!v.known[q]) {
      for (int c = 3; c < kMomentTally; ++c) EXPECT_EQ(v.value[q * kTallies + c], before.value[q * kTallies + c]);
      continue;
    }
    const glm::dvec3 f(v.value[q * kTallies + 3], v.value[q * kTallies + 4], v.value[q * kTallies + 5]);
    EXPECT_LE(glm::length(f), fluence(v, q) * (1.0 + 1e-5)) << q;
  }
  // A field whose F / phi is the same everywhere is left as it is.
  CellValues even = uniform_values(g, [](std::size_t q, int c) { return c < 3 ? float(1 + q) : c < 6 ? 0.5f * float(1 + q) : 0.0f; });
  const CellValues even_before = even;
  smooth_anisotropy(g, even);
  for (std::size_t i = 0; i < even.value.size(); ++i) EXPECT_NEAR(even.value[i], even_before.value[i], 1e-4 * (1 + even_before.value[i]));
}

TEST(LightVolumeStages, FitsRecoverALinearFieldAndStayNonNegative) {
  const CellGrid g{2, 2, 2};
  Coverage cov;
  cov.covered.assign(g.cells(), 1.0);
  cov.centroid.assign(g.cells(), glm::dvec3(0.0));
  cov.spread.assign(g.cells(), glm::dvec3(1.0 / 12.0));  // a fully covered cell: uniform in [-1/2, 1/2]^3
  // phi(u) = phi_bar + grad . (u - ubar) has first moment M = grad / 12 about the centre.
  const glm::dvec3 grad(0.2, -0.1, 0.05);
  CellValues v = uniform_values(g, [&](std::size_t, int c) {
    if (c < 3) return 1.0f;
    if (c >= kMomentTally) return float(grad[c - kMomentTally] / 12.0);
    return 0.0f;
  });
  const std::vector<float> fit = linear_fits(g, v, cov);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const std::size_t q = g.index(i, j, k);
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(fit[4 * q + a], grad[a], 1e-6);
        EXPECT_NEAR(fit[4 * q + 3], glm::dot(grad, glm::dvec3(i, j, k) + 0.5), 1e-6);
      }
  // A moment too steep for the fluence is limited so that the fit is >= 0 at every corner.
  CellValues steep = uniform_values(g, [](std::size_t, int c) { return c < 3 ? 1.0f : c >= kMomentTally ? 1.0f : 0.0f; });
  const std::vector<float> limited = linear_fits(g, steep, cov);
  const glm::dvec3 gl(limited[0], limited[1], limited[2]);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner((c & 1) ? 0.5 : -0.5, (c & 2) ? 0.5 : -0.5, (c & 4) ? 0.5 : -0.5);
    EXPECT_GE(1.0 + glm::dot(gl, corner), -1e-6);
  }
  // Cells covered under half get no fit.
  cov.covered[0] = 0.4;
  EXPECT_EQ(linear_fits(g, v, cov)[0], 0.0f);
}

TEST(LightVolumeStages, EmptyCellsFillRingByRingFromTheirFaceNeighbours) {
  const CellGrid g{6, 1, 1};  // known cells 0 and 1; 2 and 3 fill; 4 and 5 stay empty
  CellValues v = uniform_values(g, [](std::size_t q, int c) { return q < 2 ? float(1 + q + c) : 0.0f; });
  for (std::size_t q = 0; q < g.cells(); ++q) v.known[q] = q < 2;
  std::vector<float> fit(g.cells() * 4, 0.0f);
  fit[4 * 1 + 0] = 0.3f;
  fill_empty_rings(g, v, fit);
  EXPECT_EQ(v.value[2 * kTallies + 5], v.value[1 * kTallies + 5]);  // one known face neighbour: its copy
  EXPECT_EQ(v.value[3 * kTallies + 5], v.value[2 * kTallies + 5]);  // the second ring, from the first
  EXPECT_EQ(fit[4 * 3 + 0], 0.3f);
  EXPECT_EQ(v.value[4 * kTallies + 5], 0.0f);
  EXPECT_EQ(v.known[3], 1);
  EXPECT_EQ(v.known[4], 0);
}

TEST(LightVolumeStages, PackedLobesAreFractionsOfTheFluenceWithBoundedCosines) {
  const CellGrid g{3, 2, 1};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  CellValues v = uniform_values(g, [&](std::size_t, int) { return u(rng); });
  std::vector<float> fit(g.cells() * 4, 0.25f);
  LightVolume out;
  pack_light_volume(v, std::move(fit), true, glm::dvec3(0, -1, 0), out);
  ASSERT_EQ(out.fluence_rgb.size(), g.cells() * 3);
  ASSERT_EQ(out.gradient.size(), g.cells() * 4);
  for (std::size_t q = 0; q < g.cells(); ++q) {
    EXPECT_EQ(out.fluence_rgb[3 * q + 1], v.value[q * kTallies + 1]);
    EXPECT_EQ(out.quadrupole[5 * q + 4], v.value[q * kTallies + 10]);
    const double f1 = out.lobes[4 * q], f2 = out.lobes[4 * q + 2];
    EXPECT_GE(f1, 0.0);
    EXPECT_GE(f2, 0.0);
    EXPECT_LE(f1 + f2, 1.0 + 1e-6);
    EXPECT_LE(std::abs(out.lobes[4 * q + 1]), 0.95f);
    EXPECT_LE(std::abs(out.lobes[4 * q + 3]), 0.95f);
  }
  LightVolume no_fit;
  pack_light_volume(v, std::vector<float>(g.cells() * 4, 1.0f), false, glm::dvec3(0, -1, 0), no_fit);
  EXPECT_TRUE(no_fit.gradient.empty());
}

}  // namespace
}  // namespace nimbus::render::light_volume

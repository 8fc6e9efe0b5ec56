// Observational cloud statistics on optical-depth maps (support/cloud_stats.hpp): vertical
// optical depth of a hand-built grid, cloud outlines of hand-drawn shapes whose areas and
// perimeters are known exactly, and the three fits (Lovejoy's perimeter-area dimension, DeWitt's
// area exponent, Cahalan & Snider's spectral slope) on inputs built to follow a known power law.
// Recovered figures are printed with a "[cloud-stats]" prefix.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "support/cloud_stats.hpp"

namespace nimbus::test {
namespace {

// Runs f and expects std::invalid_argument whose message contains `names`.
void expect_invalid(const std::function<void()>& f, const std::string& names) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected std::invalid_argument naming '" << names << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(names), std::string::npos) << "message: " << e.what();
  }
}

OpticalDepthMap blank(int nx, int ny, double pixel_m = 1.0) {
  OpticalDepthMap m;
  m.nx = nx;
  m.ny = ny;
  m.pixel_m = pixel_m;
  m.tau.assign(size_t(nx) * size_t(ny), 0.0);
  return m;
}

double& tau(OpticalDepthMap& m, int i, int j) { return m.tau[size_t(j) * size_t(m.nx) + size_t(i)]; }

// A w x h rectangle of cloud (tau 2) with its lower-left pixel at (i0, j0).
void rect(OpticalDepthMap& m, int i0, int j0, int w, int h, double value = 2.0) {
  for (int j = j0; j < j0 + h; ++j)
    for (int i = i0; i < i0 + w; ++i) tau(m, i, j) = value;
}

// ---------------------------------------------------------------------------------------------
// vertical_optical_depth

openvdb::FloatGrid::Ptr grid_with_voxel(double voxel_m) {
  openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create(0.0f);
  g->setTransform(openvdb::math::Transform::createLinearTransform(voxel_m));
  return g;
}

// Densities are binary fractions and the factors powers of two, so every expected tau is exact.
TEST(CloudStatsDepth, ColumnIsExtinctionTimesVoxelTimesDensitySum) {
  openvdb::FloatGrid::Ptr g = grid_with_voxel(8.0);
  g->transform().postTranslate(openvdb::Vec3d(100.0, -40.0, 7.0));  // a translation is allowed
  auto acc = g->getAccessor();
  const float column[] = {0.125f, 0.25f, 0.5f, 1.0f, 2.0f};  // sum 3.875, at k = -2 .. 2
  for (int k = -2; k <= 2; ++k) acc.setValue(openvdb::Coord(2, 3, k), column[k + 2]);
  acc.setValue(openvdb::Coord(4, 1, 100), 2.0f);   // one voxel high up
  acc.setValue(openvdb::Coord(0, 0, 0), 7.0f);     // outside the columns asked for
  acc.setValue(openvdb::Coord(2, 3, 5000), 0.0f);  // active zero: adds nothing
  const double ext = 0.0625;                       // tau = ext * 8 m * sum = 0.5 * sum

  const OpticalDepthMap m = vertical_optical_depth(*g, ext, openvdb::CoordBBox(1, 0, -9, 5, 4, 9));
  ASSERT_EQ(m.nx, 5);
  ASSERT_EQ(m.ny, 5);
  ASSERT_EQ(m.tau.size(), 25u);
  EXPECT_EQ(m.pixel_m, 8.0);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      // Pixel (i, j) is column (1 + i, j); the box's z range (-9 .. 9) does not limit the sum.
      const double want = (i == 1 && j == 3) ? 0.5 * 3.875 : (i == 3 && j == 1) ? 0.5 * 2.0 : 0.0;
      EXPECT_EQ(m.at(i, j), want) << "pixel " << i << ", " << j;
    }
}

TEST(CloudStatsDepth, TilesCountOncePerVoxelOfTheirHeight) {
  openvdb::FloatGrid::Ptr g = grid_with_voxel(2.0);
  // Aligned to the 128^3 nodes, so OpenVDB stores it as tiles, not voxels.
  g->fill(openvdb::CoordBBox(0, 0, 0, 255, 255, 127), 0.25f, true);
  ASSERT_GT(g->tree().activeTileCount(), 0u);
  g->getAccessor().setValue(openvdb::Coord(258, 100, -3), 1.0f);
  // Columns x in 250 .. 260 at y = 100: x <= 255 are inside the tiles (128 voxels of 0.25).
  const OpticalDepthMap m = vertical_optical_depth(*g, 0.25, openvdb::CoordBBox(250, 100, 0, 260, 100, 0));
  ASSERT_EQ(m.nx, 11);
  ASSERT_EQ(m.ny, 1);
  for (int i = 0; i < 11; ++i) {
    const double want = (250 + i <= 255) ? 0.25 * 2.0 * 128 * 0.25 : (250 + i == 258) ? 0.25 * 2.0 * 1.0 : 0.0;
    EXPECT_EQ(m.at(i, 0), want) << "column x = " << 250 + i;
  }
}

TEST(CloudStatsDepth, RefusesBadTransformsExtinctionBoxesAndBackground) {
  openvdb::FloatGrid::Ptr good = grid_with_voxel(1.0);
  good->getAccessor().setValue(openvdb::Coord(0, 0, 0), 1.0f);
  const openvdb::CoordBBox box(0, 0, 0, 3, 3, 0);
  EXPECT_NO_THROW(vertical_optical_depth(*good, 1.0, box));

  openvdb::FloatGrid::Ptr stretched = good->deepCopy();
  openvdb::math::Transform::Ptr tall = openvdb::math::Transform::createLinearTransform(1.0);
  tall->preScale(openvdb::Vec3d(1.0, 1.0, 2.0));  // voxels twice as tall as wide
  stretched->setTransform(tall);
  expect_invalid([&] { vertical_optical_depth(*stretched, 1.0, box); }, "density");
  openvdb::FloatGrid::Ptr turned = good->deepCopy();
  openvdb::math::Transform::Ptr rotated = openvdb::math::Transform::createLinearTransform(1.0);
  rotated->postRotate(0.3, openvdb::math::Z_AXIS);  // cubic voxels, but not axis-aligned
  turned->setTransform(rotated);
  expect_invalid([&] { vertical_optical_depth(*turned, 1.0, box); }, "density");
  openvdb::FloatGrid::Ptr frustum = good->deepCopy();
  frustum->setTransform(openvdb::math::Transform::createFrustumTransform(
      openvdb::BBoxd(openvdb::Vec3d(0, 0, 0), openvdb::Vec3d(10, 10, 10)), 0.5, 10.0, 1.0));
  expect_invalid([&] { vertical_optical_depth(*frustum, 1.0, box); }, "density");

  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN(), kInf = std::numeric_limits<double>::infinity();
  for (const double ext : {0.0, -1.0, kNaN, kInf})
    expect_invalid([&] { vertical_optical_depth(*good, ext, box); }, "extinction_per_m");

  expect_invalid([&] { vertical_optical_depth(*good, 1.0, openvdb::CoordBBox()); }, "columns");
  // 2^20 x 2^20 columns: refused before allocating (a vector of 2^40 doubles would throw bad_alloc).
  expect_invalid([&] { vertical_optical_depth(*good, 1.0, openvdb::CoordBBox(0, 0, 0, 1 << 20, 1 << 20, 0)); },
                 "columns");
  expect_invalid([&] { vertical_optical_depth(*good, 1.0, openvdb::CoordBBox(0, 0, 0, 8192, 8192, 0)); },
                 "columns");  // 8193^2 > 2^26

  openvdb::FloatGrid::Ptr fogged = openvdb::FloatGrid::create(0.5f);
  expect_invalid([&] { vertical_optical_depth(*fogged, 1.0, box); }, "background");

  openvdb::FloatGrid::Ptr broken = good->deepCopy();
  broken->getAccessor().setValue(openvdb::Coord(1, 1, 4), std::numeric_limits<float>::quiet_NaN());
  expect_invalid([&] { vertical_optical_depth(*broken, 1.0, box); }, "non-finite");
}

// ---------------------------------------------------------------------------------------------
// cloud_outlines

TEST(CloudStatsOutlines, SquareOfSideSHasAreaS2AndPerimeter4S) {
  const double px = 2.5;
  for (const int s : {1, 2, 7, 30}) {
    OpticalDepthMap m = blank(s + 4, s + 6, px);
    rect(m, 2, 3, s, s);
    const auto clouds = cloud_outlines(m);
    ASSERT_EQ(clouds.size(), 1u) << "s = " << s;
    EXPECT_EQ(clouds[0].pixels, int64_t(s) * s);
    EXPECT_DOUBLE_EQ(clouds[0].area_m2, double(s) * s * px * px);
    EXPECT_DOUBLE_EQ(clouds[0].perimeter_m, 4.0 * s * px);
    EXPECT_FALSE(clouds[0].touches_edge);
  }
}

TEST(CloudStatsOutlines, LShapeAndRingsCountTheirHoleEdges) {
  // L: a 1 x 4 bar and a 2 x 1 foot; an orthogonally convex shape's perimeter is 2 (w + h).
  OpticalDepthMap l = blank(8, 8);
  rect(l, 1, 1, 1, 4);
  rect(l, 2, 1, 2, 1);
  auto clouds = cloud_outlines(l);
  ASSERT_EQ(clouds.size(), 1u);
  EXPECT_EQ(clouds[0].pixels, 6);
  EXPECT_EQ(clouds[0].perimeter_m, 2.0 * (3 + 4));

  // Rings: an outer square of side s minus a hole of side t: perimeter 4 s + 4 t.
  for (const auto& [s, t] : {std::pair{5, 1}, std::pair{7, 3}, std::pair{20, 12}}) {
    OpticalDepthMap r = blank(s + 2, s + 2);
    rect(r, 1, 1, s, s);
    const int h0 = 1 + (s - t) / 2;
    rect(r, h0, h0, t, t, 0.0);
    clouds = cloud_outlines(r);
    ASSERT_EQ(clouds.size(), 1u) << "ring " << s << " / " << t;
    EXPECT_EQ(clouds[0].pixels, int64_t(s) * s - int64_t(t) * t);
    EXPECT_EQ(clouds[0].perimeter_m, 4.0 * s + 4.0 * t);
  }
}

TEST(CloudStatsOutlines, DiagonalNeighboursAreSeparateClouds) {
  // A 4 x 4 checkerboard: 8 pixels that touch only at corners, so 8 clouds (4-connectivity).
  OpticalDepthMap m = blank(6, 6);
  for (int j = 1; j <= 4; ++j)
    for (int i = 1; i <= 4; ++i)
      if ((i + j) % 2 == 0) tau(m, i, j) = 3.0;
  const auto clouds = cloud_outlines(m);
  ASSERT_EQ(clouds.size(), 8u);
  for (const CloudOutline& c : clouds) {
    EXPECT_EQ(c.pixels, 1);
    EXPECT_EQ(c.perimeter_m, 4.0);
  }
}

TEST(CloudStatsOutlines, CloudsOnAnyBorderAreFlagged) {
  OpticalDepthMap m = blank(20, 20);
  rect(m, 5, 0, 2, 2);    // bottom row
  rect(m, 0, 5, 2, 2);    // left column
  rect(m, 18, 5, 2, 2);   // right column
  rect(m, 9, 9, 2, 2);    // inside
  rect(m, 5, 18, 2, 2);   // top row
  const auto clouds = cloud_outlines(m);
  ASSERT_EQ(clouds.size(), 5u);
  // Raster order of each cloud's first pixel: bottom, left, right, inside, top.
  const bool want[] = {true, true, true, false, true};
  for (size_t c = 0; c < 5; ++c) {
    EXPECT_EQ(clouds[c].touches_edge, want[c]) << "cloud " << c;
    EXPECT_EQ(clouds[c].pixels, 4);
    EXPECT_EQ(clouds[c].perimeter_m, 8.0);  // the map border counts as non-cloud
  }
}

TEST(CloudStatsOutlines, TauAtTheThresholdIsCloud) {
  OpticalDepthMap m = blank(9, 3);
  tau(m, 1, 1) = 1.0;                          // exactly at the default threshold: cloud
  tau(m, 3, 1) = std::nextafter(1.0, 0.0);     // just under: clear
  tau(m, 5, 1) = 0.5;                          // cloud only for threshold 0.5
  tau(m, 7, 1) = std::numeric_limits<double>::infinity();
  auto clouds = cloud_outlines(m);
  EXPECT_EQ(clouds.size(), 2u);
  clouds = cloud_outlines(m, 0.5);
  EXPECT_EQ(clouds.size(), 4u);
  clouds = cloud_outlines(m, 1.5);
  EXPECT_EQ(clouds.size(), 1u);

  expect_invalid([&] { cloud_outlines(m, std::numeric_limits<double>::quiet_NaN()); }, "threshold");
  OpticalDepthMap bad = m;
  bad.tau[4] = std::numeric_limits<double>::quiet_NaN();
  expect_invalid([&] { cloud_outlines(bad); }, "NaN");
  bad = m;
  bad.tau.pop_back();
  expect_invalid([&] { cloud_outlines(bad); }, "nx * ny");
  bad = m;
  bad.pixel_m = 0;
  expect_invalid([&] { cloud_outlines(bad); }, "pixel_m");
  expect_invalid([&] { cloud_outlines(OpticalDepthMap{}); }, "empty");
}

TEST(CloudStatsOutlines, A4096SquaredCloudNeedsNoRecursion) {
  constexpr int n = 4096;
  OpticalDepthMap m = blank(n, n);
  std::fill(m.tau.begin(), m.tau.end(), 5.0);
  auto clouds = cloud_outlines(m);
  ASSERT_EQ(clouds.size(), 1u);
  EXPECT_EQ(clouds[0].pixels, int64_t(n) * n);
  EXPECT_EQ(clouds[0].perimeter_m, 4.0 * n);
  EXPECT_TRUE(clouds[0].touches_edge);

  // A one-pixel-wide serpentine through the whole map: even rows full, joined at alternate ends.
  // It is a simple path of p pixels and p - 1 shared edges, so its perimeter is 4 p - 2 (p - 1).
  std::fill(m.tau.begin(), m.tau.end(), 0.0);
  int64_t p = 0;
  for (int j = 0; j < n; j += 2) {
    rect(m, 0, j, n, 1);
    p += n;
    if (j + 2 < n) {
      tau(m, (j / 2) % 2 == 0 ? n - 1 : 0, j + 1) = 2.0;
      ++p;
    }
  }
  clouds = cloud_outlines(m);
  ASSERT_EQ(clouds.size(), 1u);
  EXPECT_EQ(clouds[0].pixels, p);
  EXPECT_EQ(clouds[0].perimeter_m, double(2 * p + 2));
}

// ---------------------------------------------------------------------------------------------
// perimeter_area_dimension (Lovejoy 1982)

TEST(CloudStatsDimension, DigitalDiscsHaveDimensionOne) {
  // 12 discs i^2 + j^2 <= r^2, r from 5 to 200 px, side by side on one map.
  std::vector<int> radii;
  for (int t = 0; t < 12; ++t) radii.push_back(int(std::lround(5.0 * std::pow(40.0, t / 11.0))));
  int width = 2;
  for (const int r : radii) width += 2 * r + 3;
  const double px = 30.0;
  OpticalDepthMap m = blank(width, 2 * radii.back() + 5, px);
  int x = 2;
  const int cy = radii.back() + 2;
  for (const int r : radii) {
    const int cx = x + r;
    for (int j = -r; j <= r; ++j)
      for (int i = -r; i <= r; ++i)
        if (i * i + j * j <= r * r) tau(m, cx + i, cy + j) = 4.0;
    x += 2 * r + 3;
  }
  // Edge-touching and tiny clouds, which the fit must leave out: a long thin cloud along the
  // bottom edge (P / sqrt(A) = 20) and single pixels (4 pixel edges each).
  rect(m, 0, 0, width, 1);
  for (int i = 3; i < 40; i += 4) tau(m, i, 2 * radii.back() + 3) = 4.0;

  const auto clouds = cloud_outlines(m);
  std::vector<CloudOutline> discs;
  for (const CloudOutline& c : clouds)
    if (!c.touches_edge && c.pixels > 1) discs.push_back(c);
  std::sort(discs.begin(), discs.end(), [](const auto& a, const auto& b) { return a.pixels < b.pixels; });
  ASSERT_EQ(discs.size(), radii.size());
  for (size_t d = 0; d < discs.size(); ++d) {
    const int r = radii[d];
    // A digital disc is orthogonally convex with a (2r+1)^2 bounding box: P = 4 (2 r + 1).
    EXPECT_EQ(discs[d].perimeter_m, (8.0 * r + 4.0) * px) << "r = " << r;
    EXPECT_NEAR(double(discs[d].pixels), std::numbers::pi * r * r, 2.0 * std::numbers::pi * r) << "r = " << r;
  }
  const PowerLawFit fit = perimeter_area_dimension(clouds);
  std::printf("[cloud-stats] discs r = 5..200 px: D = %.4f +- %.4f over %d clouds, sqrt(A) %.0f..%.0f m\n",
              fit.exponent, fit.standard_error, fit.points, fit.x_lo, fit.x_hi);
  EXPECT_EQ(fit.points, int(radii.size()));
  EXPECT_NEAR(fit.exponent, 1.0, 0.05);
  EXPECT_NEAR(fit.x_lo, std::sqrt(double(discs.front().pixels)) * px, 1e-9);
  EXPECT_NEAR(fit.x_hi, std::sqrt(double(discs.back().pixels)) * px, 1e-9);
}

TEST(CloudStatsDimension, ExactPowerLawGivesItsExponent) {
  std::vector<CloudOutline> clouds;
  for (int c = 0; c < 40; ++c) {
    const double area = std::pow(10.0, 2.0 + 6.0 * c / 39.0);  // 1e2 .. 1e8 m^2, pixel 1 m
    clouds.push_back({int64_t(std::llround(area)), area, 3.7 * std::pow(std::sqrt(area), 1.4), false});
  }
  // Left out: clouds on the edge and under min_pixels, each far off the law.
  clouds.push_back({5000, 5000.0, 1e7, true});
  clouds.push_back({9, 9.0, 1e5, false});
  const PowerLawFit fit = perimeter_area_dimension(clouds, 10);
  EXPECT_EQ(fit.points, 40);
  EXPECT_NEAR(fit.exponent, 1.4, 1e-9);
  EXPECT_LT(fit.standard_error, 1e-9);
  EXPECT_NEAR(fit.x_lo, 10.0, 1e-6);
  EXPECT_NEAR(fit.x_hi, 1e4, 1e-6);

  expect_invalid([&] { perimeter_area_dimension({clouds[0]}); }, "at least 2");
  expect_invalid([&] { perimeter_area_dimension({clouds[3], clouds[3]}); }, "same abscissa");
  expect_invalid([&] { perimeter_area_dimension(clouds, 0); }, "min_pixels");
  std::vector<CloudOutline> bad = clouds;
  bad[5].perimeter_m = std::numeric_limits<double>::quiet_NaN();
  expect_invalid([&] { perimeter_area_dimension(bad); }, "perimeter");
}

// ---------------------------------------------------------------------------------------------
// area_exponent (DeWitt et al. 2024; DeWitt & Garrett 2024)

// n clouds with dn/dlog a ∝ a^-b above a_min: the number above a is (a / a_min)^-b, so by
// inverse-CDF sampling a = a_min u^(-1/b), u uniform in (0, 1].
std::vector<CloudOutline> power_law_clouds(double b, int n, double a_min_m2, double pixel_m, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<CloudOutline> clouds;
  for (int c = 0; c < n; ++c) {
    const double a = a_min_m2 * std::pow(1.0 - uniform(rng), -1.0 / b);
    clouds.push_back({int64_t(std::llround(a / (pixel_m * pixel_m))), a, 4.0 * std::sqrt(a), false});
  }
  return clouds;
}

// 20000 clouds a set: over 2000 seeds the fitted b fell within +-0.06 of the true b in 99 % of
// sets for b = 0.87 and b = 1.2 (with 4000 clouds, 2.4 % of the b = 1.2 sets missed by 0.08).
TEST(CloudStatsAreaExponent, RecoversExponentOfSampledPowerLaws) {
  for (const double b : {0.87, 1.2}) {
    const auto clouds = power_law_clouds(b, 20000, 1e4, 10.0, 20240109);
    const PowerLawFit fit = area_exponent(clouds);
    std::printf("[cloud-stats] %d clouds, b = %.2f: fitted b = %.4f +- %.4f over %d bins, a %.3g..%.3g m^2\n",
                int(clouds.size()), b, fit.exponent, fit.standard_error, fit.points, fit.x_lo, fit.x_hi);
    EXPECT_NEAR(fit.exponent, b, 0.08);
    EXPECT_GE(fit.points, 5);
  }
}

TEST(CloudStatsAreaExponent, BinsUnderMinCountAreDropped) {
  // One bin a decade. Bins 2, 3, 4 (centres 10^2.5, 10^3.5, 10^4.5 m^2) hold 10000, 1000, 100
  // clouds: exactly dn/dlog a ∝ a^-1. Bin 5 holds 10 and bin 6 23, under 24, and would bend the
  // line; bin 8 holds 600 clouds that all touch the edge.
  std::vector<CloudOutline> clouds;
  auto add = [&](int bin, int count, bool edge) {
    const double a = std::pow(10.0, bin + 0.5);
    for (int c = 0; c < count; ++c) clouds.push_back({int64_t(std::llround(a)), a, 4.0 * std::sqrt(a), edge});
  };
  add(2, 10000, false);
  add(3, 1000, false);
  add(4, 100, false);
  add(5, 10, false);
  add(6, 23, false);
  add(8, 600, true);
  PowerLawFit fit = area_exponent(clouds, 1, 24);
  EXPECT_EQ(fit.points, 3);
  EXPECT_NEAR(fit.exponent, 1.0, 1e-12);
  EXPECT_NEAR(fit.x_lo, std::pow(10.0, 2.5), 1e-9);
  EXPECT_NEAR(fit.x_hi, std::pow(10.0, 4.5), 1e-6);

  // With min_count 10, bins 5 and 6 enter (5 bins) and pull the fit off b = 1.
  fit = area_exponent(clouds, 1, 10);
  EXPECT_EQ(fit.points, 5);
  EXPECT_GT(std::abs(fit.exponent - 1.0), 0.05);
  // min_pixels leaves bin 2 (316 px) out.
  fit = area_exponent(clouds, 1, 24, 1000);
  EXPECT_EQ(fit.points, 2);
  EXPECT_NEAR(fit.exponent, 1.0, 1e-12);

  expect_invalid([&] { area_exponent(clouds, 1, 24, 5000); }, "at least 2");
  expect_invalid([&] { area_exponent(clouds, 0); }, "bins_per_decade");
  expect_invalid([&] { area_exponent(clouds, 5, 0); }, "min_count");
  expect_invalid([&] { area_exponent(clouds, 5, 24, 0); }, "min_pixels");
}

// ---------------------------------------------------------------------------------------------
// spectrum_slope (Cahalan & Snider 1989)

// Rows of n pixels, each an independent random-phase sum over modes m = 1 .. n/2 - 1 with
// amplitude m^(-beta/2), so the row power spectrum is ∝ k^-beta. If `same_rows`, every row is
// the first one (the map varies along x only).
OpticalDepthMap random_phase_rows(int n, int rows, double pixel_m, double beta, uint64_t seed, bool same_rows = false) {
  const size_t len = static_cast<size_t>(n);
  std::vector<double> cos_table(len), sin_table(len);
  for (int q = 0; q < n; ++q) {
    cos_table[size_t(q)] = std::cos(2 * std::numbers::pi * q / n);
    sin_table[size_t(q)] = std::sin(2 * std::numbers::pi * q / n);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> phase(0.0, 2 * std::numbers::pi);
  OpticalDepthMap m = blank(n, rows, pixel_m);
  std::vector<double> ca(size_t(n / 2)), sa(size_t(n / 2));
  for (int j = 0; j < rows; ++j) {
    if (!same_rows || j == 0)
      for (int k = 1; k < n / 2; ++k) {
        const double amp = std::pow(double(k), -beta / 2), phi = phase(rng);
        ca[size_t(k)] = amp * std::cos(phi);
        sa[size_t(k)] = amp * std::sin(phi);
      }
    for (int i = 0; i < n; ++i) {
      // cos(2 pi k i / n + phi) = cos(theta) cos(phi) - sin(theta) sin(phi)
      double v = 10.0;
      for (int k = 1; k < n / 2; ++k) {
        const size_t q = size_t(k) * size_t(i) % size_t(n);
        v += ca[size_t(k)] * cos_table[q] - sa[size_t(k)] * sin_table[q];
      }
      tau(m, i, j) = v;
    }
  }
  return m;
}

OpticalDepthMap transposed(const OpticalDepthMap& m) {
  OpticalDepthMap t = blank(m.ny, m.nx, m.pixel_m);
  for (int j = 0; j < m.ny; ++j)
    for (int i = 0; i < m.nx; ++i) tau(t, j, i) = m.at(i, j);
  return t;
}

TEST(CloudStatsSpectrum, RecoversSlopeOfRandomPhaseRows) {
  // 1024 px of 20 m along x, 64 rows; fitted between 200 m and 5 km as Cahalan & Snider.
  for (const double beta : {0.0, 5.0 / 3.0, 3.0}) {
    const OpticalDepthMap m = random_phase_rows(1024, 64, 20.0, beta, 1989);
    const PowerLawFit fit = spectrum_slope(m, MapAxis::X, 200.0, 5000.0);
    std::printf("[cloud-stats] rows with P ∝ k^-%.3f: slope %.4f +- %.4f over %d bins, k %.3g..%.3g /m\n", beta,
                fit.exponent, fit.standard_error, fit.points, fit.x_lo, fit.x_hi);
    EXPECT_NEAR(fit.exponent, -beta, 0.15) << "beta = " << beta;
    // 1/k spans 204.8 .. 4096 m (modes 5 .. 100): about 1.3 decades at 10 bins a decade.
    EXPECT_GE(fit.points, 10);
    EXPECT_GE(fit.x_lo, 1 / 5000.0);
    EXPECT_LE(fit.x_hi, 1 / 200.0);
  }
}

TEST(CloudStatsSpectrum, AxisChoosesRowsOrColumns) {
  // Every row the same: tau varies along x only.
  const OpticalDepthMap m = random_phase_rows(512, 32, 20.0, 5.0 / 3.0, 7, true);
  // Along x it fits (one realisation repeated, so its slope is noisy: not checked here).
  const PowerLawFit along_x = spectrum_slope(m, MapAxis::X, 200.0, 5000.0);
  EXPECT_TRUE(std::isfinite(along_x.exponent));
  EXPECT_GE(along_x.points, 10);
  // Along y every column is constant: there is no power to fit, and it says so.
  expect_invalid([&] { spectrum_slope(m, MapAxis::Y, 200.0, 600.0); }, "no power along y");
  // The transposed map along y is the original along x.
  const PowerLawFit along_y = spectrum_slope(transposed(m), MapAxis::Y, 200.0, 5000.0);
  EXPECT_NEAR(along_y.exponent, along_x.exponent, 1e-9);
  EXPECT_EQ(along_y.points, along_x.points);
}

TEST(CloudStatsSpectrum, RefusesWavelengthsTheMapCannotResolve) {
  const OpticalDepthMap m = random_phase_rows(256, 4, 20.0, 2.0, 3);  // lines of 5120 m
  expect_invalid([&] { spectrum_slope(m, MapAxis::X, 30.0, 1000.0); }, "Nyquist");
  expect_invalid([&] { spectrum_slope(m, MapAxis::X, 200.0, 6000.0); }, "line length");
  expect_invalid([&] { spectrum_slope(m, MapAxis::X, 500.0, 500.0); }, "lambda_lo_m");
  expect_invalid([&] { spectrum_slope(m, MapAxis::X, std::nan(""), 500.0); }, "lambda_lo_m");
  // 4000 .. 5120 m holds one mode (5120 m): one bin, no slope.
  expect_invalid([&] { spectrum_slope(m, MapAxis::X, 4000.0, 5120.0); }, "at least 2");
  // Columns are 4 px (80 m) long: 200 m is over their length.
  expect_invalid([&] { spectrum_slope(m, MapAxis::Y, 40.0, 200.0); }, "line length along y");
  OpticalDepthMap bad = m;
  bad.tau[17] = std::numeric_limits<double>::infinity();
  expect_invalid([&] { spectrum_slope(bad, MapAxis::X, 200.0, 5000.0); }, "not finite");
}

}  // namespace
}  // namespace nimbus::test

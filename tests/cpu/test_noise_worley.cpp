// Worley (cellular) noise and Perlin-Worley noise: the nearest-point search against brute force,
// range, mean and standard deviation against an independent Monte Carlo of the same point
// process, Lipschitz bounds in space and time, periodicity, and the Perlin-Worley remap's
// bounds. (Batched SIMD == scalar is in test_noise_props_batch.cpp, with the other kinds.)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "nimbus/noise/noise.hpp"
#include "nimbus/noise/perlin_worley.hpp"
#include "support/noise_props.hpp"

namespace nimbus::noise {
namespace {

using test::Rng;

NoiseParams worley(uint32_t seed = 11) {
  NoiseParams p;
  p.kind = Kind::Worley;
  p.seed = seed;
  return p;
}

// F1 by brute force: the nearest of the feature points of all 7^3 cells around x, in double.
double brute_f1(const NoiseField& f, double x, double y, double z) {
  const int64_t cx = int64_t(std::floor(x)), cy = int64_t(std::floor(y)), cz = int64_t(std::floor(z));
  double best = 1e300;
  for (int64_t k = cz - 3; k <= cz + 3; ++k)
    for (int64_t j = cy - 3; j <= cy + 3; ++j)
      for (int64_t i = cx - 3; i <= cx + 3; ++i) {
        const auto p = worley_feature_point(f, 0, i, j, k);
        const double d2 = (p[0] - x) * (p[0] - x) + (p[1] - y) * (p[1] - y) + (p[2] - z) * (p[2] - z);
        best = std::min(best, d2);
      }
  return std::sqrt(best);
}

TEST(NoiseWorley, NearestPointMatchesBruteForce) {
  // Static and animated; the rare samples whose nearest point lies beyond the 27 nearest cells
  // (F1 > 1) must be found too, so enough samples are drawn to meet some.
  for (bool animated : {false, true}) {
    NoiseParams p = worley(3);
    if (animated) p.time = 5.37;
    const NoiseField f(p);
    Rng rng(animated ? 41 : 40);
    double worst = 0.0;
    int far = 0;
    const int n = 200000;
    for (int s = 0; s < n; ++s) {
      const double x = rng.uniform(-500, 500), y = rng.uniform(-500, 500), z = rng.uniform(-500, 500);
      const double want = brute_f1(f, x, y, z);
      const double got = 1.0 - double(f.eval(x, y, z));
      worst = std::max(worst, std::fabs(got - want));
      far += want > 1.0;
      ASSERT_NEAR(got, want, 2e-6) << "at (" << x << ", " << y << ", " << z << ")" << (animated ? " animated" : "");
    }
    std::printf("Worley F1 vs brute force (%s): %d samples, worst |error| %.2e, %d with F1 > 1\n",
                animated ? "animated" : "static", n, worst, far);
    EXPECT_GT(far, 0) << "no sample exercised the outer shell";
  }
}

TEST(NoiseWorley, RangeMeanAndSdMatchAnIndependentMonteCarlo) {
  // The same point process (one uniform point per unit cell) drawn with std::mt19937_64.
  std::mt19937_64 gen(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double s1 = 0.0, s2 = 0.0;
  const int m = 300000;
  for (int s = 0; s < m; ++s) {
    const double x[3] = {u(gen), u(gen), u(gen)};
    double best = 1e300;
    for (int dz = -2; dz <= 2; ++dz)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const double e[3] = {dx + u(gen) - x[0], dy + u(gen) - x[1], dz + u(gen) - x[2]};
          best = std::min(best, e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        }
    const double f1 = std::sqrt(best);
    s1 += f1;
    s2 += f1 * f1;
  }
  const double mc_mean = s1 / m, mc_sd = std::sqrt(s2 / m - mc_mean * mc_mean);
  EXPECT_NEAR(mc_mean, kWorleyMeanF1, 0.0015);
  EXPECT_NEAR(mc_sd, kWorleySdF1, 0.0015);

  for (bool animated : {false, true}) {
    NoiseParams p = worley(9);
    if (animated) p.time = 2.71;
    const NoiseField f(p);
    EXPECT_NEAR(f.expected_mean(), 1.0 - kWorleyMeanF1, 1e-12);
    EXPECT_NEAR(f.expected_sd(), kWorleySdF1, 1e-12);
    // Samples 0.731 lattice units apart over 80^3: nearly independent across cells.
    GridSpec g;
    g.origin = {-13.1, 7.7, 101.3};
    g.spacing = 0.731;
    g.res = {80, 80, 80};
    std::vector<float> v(size_t(g.count()));
    evaluate_grid(f, g, v);
    double a = 0.0, b = 0.0, lo = 1e9, hi = -1e9;
    for (float x : v) {
      a += x;
      b += double(x) * x;
      lo = std::min(lo, double(x));
      hi = std::max(hi, double(x));
    }
    const double mean = a / v.size(), sd = std::sqrt(b / v.size() - mean * mean);
    std::printf("Worley 1 - F1 (%s): mean %.4f (MC %.4f), sd %.4f (MC %.4f), range [%.3f, %.3f]\n",
                animated ? "animated" : "static", mean, 1.0 - mc_mean, sd, mc_sd, lo, hi);
    EXPECT_NEAR(mean, 1.0 - mc_mean, 0.004);
    EXPECT_NEAR(sd, mc_sd, 0.004);
    EXPECT_GE(lo, 1.0 - std::sqrt(3.0));
    EXPECT_LE(hi, 1.0);
    EXPECT_GT(hi, 0.99);  // samples land next to feature points
  }
}

TEST(NoiseWorley, LipschitzInSpaceAndTime) {
  // F1 is 1-Lipschitz in the sample and in each point; the points move at most
  // 1.25 sqrt(3) lattice units per time unit.
  NoiseParams p = worley(5);
  Rng rng(7);
  for (int s = 0; s < 20000; ++s) {
    const double x = rng.uniform(-50, 50), y = rng.uniform(-50, 50), z = rng.uniform(-50, 50);
    const double t = rng.uniform(-20, 20), h = rng.uniform(-0.05, 0.05), dt = rng.uniform(-0.05, 0.05);
    p.time = t;
    const NoiseField a(p);
    p.time = t + dt;
    const NoiseField b(p);
    const double n0 = a.eval(x, y, z);
    ASSERT_LE(std::fabs(a.eval(x + h, y - h, z + h) - n0), std::sqrt(3.0) * std::fabs(h) + 2e-6);
    ASSERT_LE(std::fabs(b.eval(x, y, z) - n0), 1.25 * std::sqrt(3.0) * std::fabs(dt) + 4e-6) << "t " << t;
  }
}

TEST(NoiseWorley, PeriodicFieldsRepeat) {
  NoiseParams p = worley(2);
  p.fractal = Fractal::Fbm;
  p.octaves = 3;
  p.period = {3, 5, 8};
  const NoiseField f(p);
  Rng rng(1);
  for (int s = 0; s < 5000; ++s) {
    const double x = rng.dyadic(-40, 40, 20), y = rng.dyadic(-40, 40, 20), z = rng.dyadic(-40, 40, 20);
    const float v = f.eval(x, y, z);
    ASSERT_EQ(test::bits(v), test::bits(f.eval(x + 3, y, z)));
    ASSERT_EQ(test::bits(v), test::bits(f.eval(x, y - 5, z)));
    ASSERT_EQ(test::bits(v), test::bits(f.eval(x, y, z + 16)));
  }
  // Period 1 still finds the nearest of a lattice of copies of one point.
  NoiseParams one = worley(4);
  one.period = {1, 1, 1};
  const NoiseField g(one);
  const auto c = worley_feature_point(g, 0, 0, 0, 0);
  for (int s = 0; s < 2000; ++s) {
    const double x = rng.uniform(-5, 5), y = rng.uniform(-5, 5), z = rng.uniform(-5, 5);
    double best = 1e9;
    for (int k = -1; k <= 1; ++k)
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          const double e[3] = {std::floor(x) + i + (c[0]) - x, std::floor(y) + j + c[1] - y, std::floor(z) + k + c[2] - z};
          best = std::min(best, e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        }
    ASSERT_NEAR(1.0 - g.eval(x, y, z), std::sqrt(best), 2e-6);
  }
}

TEST(NoiseWorley, FeaturePointsAreUniformInTheirCells) {
  // Mean 1/2 and variance 1/12 per coordinate, static and moving.
  for (bool animated : {false, true}) {
    NoiseParams p = worley(8);
    if (animated) p.time = 0.61;
    const NoiseField f(p);
    double s[3] = {0, 0, 0}, q[3] = {0, 0, 0};
    const int n = 40000;
    for (int c = 0; c < n; ++c) {
      const auto pt = worley_feature_point(f, 0, c % 37, (c / 37) % 41, c / (37 * 41));
      const int64_t cell[3] = {c % 37, (c / 37) % 41, c / (37 * 41)};
      for (int a = 0; a < 3; ++a) {
        const double o = pt[a] - double(cell[a]);
        ASSERT_GE(o, 0.0);
        ASSERT_LE(o, 1.0);
        s[a] += o;
        q[a] += o * o;
      }
    }
    for (int a = 0; a < 3; ++a) {
      const double mean = s[a] / n, var = q[a] / n - mean * mean;
      EXPECT_NEAR(mean, 0.5, 0.006) << "axis " << a << (animated ? " animated" : "");
      EXPECT_NEAR(var, 1.0 / 12.0, 0.003) << "axis " << a << (animated ? " animated" : "");
    }
  }
  EXPECT_THROW(worley_feature_point(NoiseField(NoiseParams{}), 0, 0, 0, 0), std::invalid_argument);
}

TEST(NoisePerlinWorley, RemapBoundsAndBatchBits) {
  PerlinWorleyParams p;
  p.frequency = 0.37;
  p.seed = 12;
  p.time = 1.5;
  const PerlinWorleyField f(p);
  Rng rng(3);
  std::vector<std::array<double, 3>> pts(4099);
  for (auto& q : pts) q = {rng.uniform(-90, 90), rng.uniform(-90, 90), rng.uniform(-90, 90)};
  std::vector<float> got(pts.size());
  f.evaluate_points(pts, got);
  double a = 0.0, b = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const float v = f.eval(pts[i][0], pts[i][1], pts[i][2]);
    ASSERT_EQ(test::bits(v), test::bits(got[i]));
    const float w = std::clamp(f.worley().eval(pts[i][0], pts[i][1], pts[i][2]), 0.0f, 1.0f);
    // remap(P, 0, 1, W, 1) lies in [W, 1].
    ASSERT_GE(v, w);
    ASSERT_LE(v, 1.0f);
    a += v;
    b += double(v) * v;
  }
  const double mean = a / pts.size(), sd = std::sqrt(b / pts.size() - mean * mean);
  std::printf("Perlin-Worley: mean %.3f, sd %.3f over %zu points\n", mean, sd, pts.size());
  // W's mean is 1 - 0.52 and P's is 1/2, so E[W + P (1 - W)] is near 0.48 + 0.5 * 0.52 = 0.74.
  EXPECT_NEAR(mean, 0.74, 0.05);
  EXPECT_GT(sd, 0.05);
  // The limits of the remap: P = 0 gives W, P = 1 gives 1.
  EXPECT_FLOAT_EQ(f.combine(-1e6f, 0.3f), 0.3f);
  EXPECT_FLOAT_EQ(f.combine(1e6f, 0.3f), 1.0f);
}

}  // namespace
}  // namespace nimbus::noise

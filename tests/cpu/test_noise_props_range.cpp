// Range of the noise module: the exact bound of improved-Perlin gradient noise (checked
// against an independent figure and an independent search), the adversarial gradient
// configuration that reaches it, and >= 10^7 random samples of every public output lying
// inside NoiseField::range().
//
// Independent figures (computed apart from nimbus: the best gradient per corner, then the point
// optimised over the lattice cell): max |n| = 1.0363538 for 3D improved Perlin noise (12 edge
// gradients, quintic fade), reached at p ~ (0.355257, 0.481492, 0.5) and its mirror images;
// FastNoiseLite's scale 0.964921414852 is its reciprocal.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "nimbus/noise/noise.hpp"
#include "support/noise_props.hpp"

namespace nimbus::noise {
namespace {

using test::Moments;
using test::Rng;

constexpr double kReferenceBound3 = 1.0363538;          // computed independently
constexpr double kReferencePoint3[3] = {0.355257, 0.481492, 0.5};

double fade_d(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// ---- Independent gradient tables --------------------------------------------------------

// The 12 cube-edge gradients as returned by the library (validated below to be exactly the
// 12 distinct vectors with two components +-1 and one 0).
std::array<std::array<double, 3>, 12> edge_table3() {
  std::array<std::array<double, 3>, 12> g{};
  for (int i = 0; i < 12; ++i) {
    float v[3];
    edge_gradient3(i, v);
    for (int a = 0; a < 3; ++a) g[i][a] = v[a];
  }
  return g;
}

// The 32 tesseract-edge gradients, decoded from the documented index layout
// (index = zero_axis * 8 + sign bits; the three non-zero axes in increasing order take the
// sign bits 1, 2, 4; a set bit means -1). Checked against gradient_noise_cell4 below.
std::array<std::array<double, 4>, 32> edge_table4() {
  std::array<std::array<double, 4>, 32> g{};
  for (int i = 0; i < 32; ++i) {
    const int zero_axis = i >> 3;
    int j = 0;
    for (int a = 0; a < 4; ++a) {
      if (a == zero_axis) {
        g[i][a] = 0.0;
        continue;
      }
      g[i][a] = ((i >> j) & 1) ? -1.0 : 1.0;
      ++j;
    }
  }
  return g;
}

// Raw gradient noise in one cell for given gradient vectors per corner, in double.
template <int Dims, class Table>
double cell_value(const Table& table, const double* p, const int* idx) {
  double sum = 0.0;
  for (int c = 0; c < (1 << Dims); ++c) {
    double w = 1.0, dot = 0.0;
    for (int a = 0; a < Dims; ++a) {
      const bool hi = (c >> a) & 1;
      const double d = hi ? p[a] - 1.0 : p[a];
      w *= hi ? fade_d(p[a]) : 1.0 - fade_d(p[a]);
      dot += table[idx[c]][a] * d;
    }
    sum += w * dot;
  }
  return sum;
}

// For every corner, the gradient index maximising (sign = +1) or minimising (-1) g . d_c,
// found by trying every gradient (no sorting trick, unlike best_gradient_sum).
template <int Dims, class Table>
void best_indices(const Table& table, const double* p, double sign, int* idx) {
  for (int c = 0; c < (1 << Dims); ++c) {
    double best = -1e300;
    for (int i = 0; i < int(table.size()); ++i) {
      double dot = 0.0;
      for (int a = 0; a < Dims; ++a) dot += table[i][a] * (((c >> a) & 1) ? p[a] - 1.0 : p[a]);
      if (sign * dot > best) {
        best = sign * dot;
        idx[c] = i;
      }
    }
  }
}

template <int Dims, class Table>
double brute_best_sum(const Table& table, const double* p) {
  int idx[1 << Dims];
  best_indices<Dims>(table, p, 1.0, idx);
  return cell_value<Dims>(table, p, idx);
}

// All images of p under the symmetries of the cube (axis permutations and mirrors t -> 1-t).
std::vector<std::array<double, 3>> cube_images(const double* p) {
  std::vector<std::array<double, 3>> out;
  int perm[3] = {0, 1, 2};
  do {
    for (int m = 0; m < 8; ++m) {
      std::array<double, 3> q;
      for (int a = 0; a < 3; ++a) q[a] = (m >> a & 1) ? 1.0 - p[perm[a]] : p[perm[a]];
      out.push_back(q);
    }
  } while (std::next_permutation(perm, perm + 3));
  return out;
}

TEST(NoisePropsRange, EdgeGradientTable3IsTheTwelveCubeEdges) {
  const auto g = edge_table3();
  for (int i = 0; i < 12; ++i) {
    int zeros = 0, units = 0;
    for (double c : g[i]) {
      zeros += c == 0.0;
      units += std::fabs(c) == 1.0;
    }
    EXPECT_EQ(zeros, 1) << "gradient " << i;
    EXPECT_EQ(units, 2) << "gradient " << i;
    for (int j = 0; j < i; ++j) EXPECT_NE(g[i], g[j]) << "gradients " << i << " and " << j;
  }
}

TEST(NoisePropsRange, EdgeGradientTable4MatchesKernel) {
  // With every corner on gradient i, gradient_noise_cell4 must equal the double-precision
  // sum for the decoded vector; this pins the decoding used by the adversarial test.
  const auto g = edge_table4();
  Rng rng(44);
  for (int trial = 0; trial < 50; ++trial) {
    float t[4];
    double p[4];
    for (int a = 0; a < 4; ++a) {
      t[a] = static_cast<float>(rng.uniform());
      p[a] = t[a];
    }
    for (int i = 0; i < 32; ++i) {
      int idx[16];
      std::fill(idx, idx + 16, i);
      const double want = cell_value<4>(g, p, idx);
      EXPECT_NEAR(gradient_noise_cell4(t, idx), want, 2e-6) << "index " << i;
    }
    // Mixed indices as well.
    int idx[16];
    for (int& k : idx) k = int(rng.integer(0, 31));
    EXPECT_NEAR(gradient_noise_cell4(t, idx), cell_value<4>(g, p, idx), 2e-6);
  }
}

TEST(NoisePropsRange, GradientBound3MatchesIndependentFigure) {
  const BoundResult b = gradient_noise_bound(3);
  RecordProperty("bound3", std::to_string(b.bound));
  std::printf("gradient_noise_bound(3) = %.9f at (%.6f, %.6f, %.6f); reference %.7f\n", b.bound,
              b.p[0], b.p[1], b.p[2], kReferenceBound3);
  EXPECT_NEAR(b.bound, kReferenceBound3, 1e-6);
  EXPECT_NEAR(double(kGradientBound3), kReferenceBound3, 1e-6);
  // The scale must not exceed 1 / bound (else the scaled extremum exceeds 1).
  EXPECT_LE(double(kGradientScale3) * b.bound, 1.0);

  // The point is a mirror image / permutation of the reference point.
  bool found = false;
  for (const auto& q : cube_images(kReferencePoint3)) {
    bool close = true;
    for (int a = 0; a < 3; ++a) close = close && std::fabs(q[a] - b.p[a]) <= 5e-6;
    found = found || close;
  }
  EXPECT_TRUE(found) << "(" << b.p[0] << ", " << b.p[1] << ", " << b.p[2]
                     << ") is no symmetric image of (0.355257, 0.481492, 0.5)";

  // Independent brute force: the best-gradient sum at the reported point is the bound, and
  // no point of a fine grid over the cell (nor a random cloud around p) exceeds it.
  const auto g = edge_table3();
  EXPECT_NEAR(brute_best_sum<3>(g, b.p), b.bound, 1e-12);
  double grid_max = 0.0;
  const int n = 40;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        const double p[3] = {double(i) / n, double(j) / n, double(k) / n};
        grid_max = std::max(grid_max, brute_best_sum<3>(g, p));
      }
  EXPECT_LE(grid_max, b.bound + 1e-12);
  Rng rng(3);
  for (int trial = 0; trial < 20000; ++trial) {
    const double r = trial < 10000 ? 1e-2 : 1e-4;
    double p[3];
    for (int a = 0; a < 3; ++a) p[a] = std::clamp(b.p[a] + rng.uniform(-r, r), 0.0, 1.0);
    ASSERT_LE(brute_best_sum<3>(g, p), b.bound + 1e-12);
    // The library's sort-based best sum agrees with trying every gradient.
    ASSERT_NEAR(best_gradient_sum(3, p), brute_best_sum<3>(g, p), 1e-12);
  }
}

TEST(NoisePropsRange, GradientBound4IsTheMaximumOfAnIndependentSearch) {
  const BoundResult b = gradient_noise_bound(4);
  std::printf("gradient_noise_bound(4) = %.9f at (%.6f, %.6f, %.6f, %.6f)\n", b.bound, b.p[0],
              b.p[1], b.p[2], b.p[3]);
  RecordProperty("bound4", std::to_string(b.bound));
  EXPECT_NEAR(double(kGradientBound4), b.bound, 1e-6);
  EXPECT_LE(double(kGradientScale4) * b.bound, 1.0);
  const auto g = edge_table4();
  EXPECT_NEAR(brute_best_sum<4>(g, b.p), b.bound, 1e-12);
  double grid_max = 0.0;
  const int n = 12;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k)
        for (int l = 0; l <= n; ++l) {
          const double p[4] = {double(i) / n, double(j) / n, double(k) / n, double(l) / n};
          grid_max = std::max(grid_max, brute_best_sum<4>(g, p));
        }
  EXPECT_LE(grid_max, b.bound + 1e-12);
  Rng rng(4);
  for (int trial = 0; trial < 5000; ++trial) {
    const double r = trial < 2500 ? 1e-2 : 1e-4;
    double p[4];
    for (int a = 0; a < 4; ++a) p[a] = std::clamp(b.p[a] + rng.uniform(-r, r), 0.0, 1.0);
    ASSERT_LE(brute_best_sum<4>(g, p), b.bound + 1e-12);
    ASSERT_NEAR(best_gradient_sum(4, p), brute_best_sum<4>(g, p), 1e-12);
  }
}

TEST(NoisePropsRange, AdversarialGradientsReachTheBound3) {
  const BoundResult b = gradient_noise_bound(3);
  const auto g = edge_table3();
  float worst_scaled = 0.0f;
  for (const auto& q : cube_images(b.p)) {
    const float t[3] = {float(q[0]), float(q[1]), float(q[2])};
    const double p[3] = {t[0], t[1], t[2]};
    for (double sign : {1.0, -1.0}) {
      int idx[8];
      best_indices<3>(g, p, sign, idx);
      const float raw = gradient_noise_cell(t, idx);
      EXPECT_NEAR(double(raw), sign * kReferenceBound3, 1e-6) << "image " << q[0] << "," << q[1] << "," << q[2];
      const float scaled = raw * kGradientScale3;
      EXPECT_LE(std::fabs(scaled), 1.0f);
      EXPECT_GT(std::fabs(scaled), 0.99999f);
      worst_scaled = std::max(worst_scaled, std::fabs(scaled));
    }
  }
  std::printf("adversarial 3D: max |scaled| = %.8f\n", double(worst_scaled));
  RecordProperty("adversarial3_scaled", std::to_string(worst_scaled));

  // Any gradient choice anywhere in the cell stays within the bound.
  Rng rng(33);
  for (int trial = 0; trial < 200000; ++trial) {
    float t[3];
    for (float& c : t) c = static_cast<float>(rng.uniform());
    int idx[8];
    for (int& k : idx) k = int(rng.integer(0, 11));
    const float v = gradient_noise_cell(t, idx);
    ASSERT_LE(std::fabs(v), kReferenceBound3 + 1e-6);
    ASSERT_LE(std::fabs(v * kGradientScale3), 1.0f);
  }
}

TEST(NoisePropsRange, AdversarialGradientsReachTheBound4) {
  const BoundResult b = gradient_noise_bound(4);
  const auto g = edge_table4();
  const float t[4] = {float(b.p[0]), float(b.p[1]), float(b.p[2]), float(b.p[3])};
  const double p[4] = {t[0], t[1], t[2], t[3]};
  for (double sign : {1.0, -1.0}) {
    int idx[16];
    best_indices<4>(g, p, sign, idx);
    const float raw = gradient_noise_cell4(t, idx);
    EXPECT_NEAR(double(raw), sign * double(kGradientBound4), 1e-6);
    EXPECT_NEAR(double(raw), sign * b.bound, 1e-6);
    const float scaled = raw * kGradientScale4;
    std::printf("adversarial 4D: raw %.8f scaled %.8f\n", double(raw), double(scaled));
    EXPECT_LE(std::fabs(scaled), 1.0f);
    EXPECT_GT(std::fabs(scaled), 0.99999f);
  }
  Rng rng(34);
  for (int trial = 0; trial < 100000; ++trial) {
    float tt[4];
    for (float& c : tt) c = static_cast<float>(rng.uniform());
    int idx[16];
    for (int& k : idx) k = int(rng.integer(0, 31));
    const float v = gradient_noise_cell4(tt, idx);
    ASSERT_LE(std::fabs(v * kGradientScale4), 1.0f);
  }
}

// ---- Sampled ranges -----------------------------------------------------------------------

struct RangeCase {
  std::string name;
  NoiseParams params;
  int64_t samples;
};
void PrintTo(const RangeCase& c, std::ostream* os) { *os << c.name; }


NoiseParams make(Kind kind, Fractal fractal, int octaves = 6) {
  NoiseParams p;
  p.kind = kind;
  p.fractal = fractal;
  p.octaves = octaves;
  p.seed = 1234;
  return p;
}

// At least 10^7 samples per kind in total: 10^7 for the single noise, 2 * 10^6 for each
// fractal sum and animated variant. Projected wavelet noise is evaluated one lane at a time
// (tens of microseconds per sample), so it gets fewer.
std::vector<RangeCase> range_cases() {
  std::vector<RangeCase> cases;
  const int64_t kMany = 10'000'000, kSome = 2'000'000, kFew = 500'000;
  const std::pair<Kind, const char*> kinds[] = {
      {Kind::Value, "Value"}, {Kind::Gradient, "Gradient"}, {Kind::Wavelet, "Wavelet"}};
  for (auto [kind, kname] : kinds) {
    const std::string k = kname;
    cases.push_back({k + "Static", make(kind, Fractal::None), kMany});
    NoiseParams anim = make(kind, Fractal::None);
    anim.time = 0.37;
    cases.push_back({k + "Animated", anim, kSome});
    anim.time = -12.85;
    cases.push_back({k + "AnimatedNegativeTime", anim, kFew});
    cases.push_back({k + "Fbm6", make(kind, Fractal::Fbm), kSome});
    cases.push_back({k + "Turbulence6", make(kind, Fractal::Turbulence), kSome});
    cases.push_back({k + "Ridged6", make(kind, Fractal::Ridged), kSome});
    NoiseParams afbm = make(kind, Fractal::Fbm);
    afbm.time = 0.61;
    cases.push_back({k + "Fbm6Animated", afbm, kFew});
    NoiseParams gain1 = make(kind, Fractal::Ridged, 3);
    gain1.gain = 1.0;
    gain1.lacunarity = 1.7;
    cases.push_back({k + "Ridged3Gain1", gain1, kFew});
  }
  NoiseParams proj = make(Kind::Wavelet, Fractal::None);
  proj.projected = true;
  proj.normal = {0.3, -0.5, 0.81};
  cases.push_back({"WaveletProjected", proj, 200'000});
  proj.normal = {0.0, 0.0, 1.0};
  cases.push_back({"WaveletProjectedAxis", proj, 100'000});
  NoiseParams projf = make(Kind::Wavelet, Fractal::Fbm, 4);
  projf.projected = true;
  projf.normal = {1.0, 1.0, 1.0};
  projf.time = 0.4;
  cases.push_back({"WaveletProjectedFbm4Animated", projf, 20'000});
  NoiseParams projt = projf;
  projt.fractal = Fractal::Turbulence;
  projt.time.reset();
  cases.push_back({"WaveletProjectedTurbulence4", projt, 30'000});
  return cases;
}

class NoisePropsSampledRange : public ::testing::TestWithParam<RangeCase> {};

TEST_P(NoisePropsSampledRange, EveryOutputLiesInRange) {
  const RangeCase& c = GetParam();
  const NoiseField field(c.params);
  const Range r = field.range();
  const Moments m = test::random_moments(field, c.samples, 0xa11ce + c.samples,
                                         {-1000.0, -1000.0, -1000.0}, {1000.0, 1000.0, 1000.0});
  std::printf("range %-30s [%+.7f, %+.7f] documented [%g, %g]  (%s)\n", c.name.c_str(),
              double(m.min), double(m.max), double(r.lo), double(r.hi), m.str().c_str());
  RecordProperty("observed_min", std::to_string(m.min));
  RecordProperty("observed_max", std::to_string(m.max));
  EXPECT_EQ(m.non_finite, 0) << test::describe(c.params);
  EXPECT_EQ(m.n, c.samples);
  EXPECT_GE(m.min, r.lo) << test::describe(c.params);
  EXPECT_LE(m.max, r.hi) << test::describe(c.params);
  // The documented ranges are [-1, 1] for single noises and fBm, [0, 1] for folded sums.
  if (c.params.fractal == Fractal::Turbulence || c.params.fractal == Fractal::Ridged) {
    EXPECT_EQ(r.lo, 0.0f);
    EXPECT_EQ(r.hi, 1.0f);
  } else {
    EXPECT_EQ(r.lo, -1.0f);
    EXPECT_EQ(r.hi, 1.0f);
  }
  // Not degenerate: the samples spread over a real part of the range.
  EXPECT_GT(m.max - m.min, 0.1f) << test::describe(c.params);
}

INSTANTIATE_TEST_SUITE_P(AllKinds, NoisePropsSampledRange, ::testing::ValuesIn(range_cases()),
                         [](const ::testing::TestParamInfo<RangeCase>& param_info) { return param_info.param.name; });

}  // namespace
}  // namespace nimbus::noise

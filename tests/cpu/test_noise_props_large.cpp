// Large coordinates: with double input, noise near |x| = 2^30 lattice units (and fBm whose top
// octave runs at 2^49) has the same statistics as near the origin: mean, sd (within 2 % of
// expected_sd()), and the correlation of samples 0.25 lattice units apart (within 0.02).
#include <gtest/gtest.h>

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

struct LagStats {
  Moments m;
  double lag_corr[3] = {0, 0, 0};  // correlation of f(p) and f(p + lag e_axis)
};

// Samples around `center` (each axis center[a] + uniform[-1000, 1000]), and the same points
// moved by `lag` along each axis.
LagStats sample(const NoiseField& f, const std::array<double, 3>& center, int64_t n, double lag,
                uint64_t seed) {
  Rng rng(seed);
  std::vector<std::array<double, 3>> pts(static_cast<size_t>(n));
  for (auto& q : pts)
    for (int a = 0; a < 3; ++a) q[a] = center[a] + rng.uniform(-1000.0, 1000.0);
  std::vector<float> v(pts.size()), w(pts.size());
  evaluate_points(f, pts, v);
  LagStats s;
  for (float x : v) s.m.add(x);
  const double mean = s.m.mean(), var = s.m.sd() * s.m.sd();
  for (int a = 0; a < 3; ++a) {
    auto moved = pts;
    for (auto& q : moved) q[a] += lag;
    evaluate_points(f, moved, w);
    double cov = 0.0;
    for (size_t i = 0; i < v.size(); ++i) cov += (double(v[i]) - mean) * (double(w[i]) - mean);
    s.lag_corr[a] = cov / double(v.size()) / var;
  }
  return s;
}

struct LargeCase {
  std::string name;
  NoiseParams params;
  std::array<double, 3> far;
};
void PrintTo(const LargeCase& c, std::ostream* os) { *os << c.name; }

std::vector<LargeCase> large_cases() {
  const double p30 = 1073741824.0;  // 2^30
  std::vector<LargeCase> out;
  for (Kind k : {Kind::Value, Kind::Gradient}) {
    const std::string kn = k == Kind::Value ? "Value" : "Gradient";
    NoiseParams p;
    p.kind = k;
    p.seed = 404;
    out.push_back({kn + "At2p30", p, {p30, -p30, p30 + 12345.5}});
    out.push_back({kn + "AtMinus2p30", p, {-p30, -p30 - 777.25, -p30}});
    NoiseParams a = p;
    a.time = 0.3;
    out.push_back({kn + "AnimatedAt2p30", a, {p30, p30, -p30}});
    NoiseParams fbm = p;
    fbm.fractal = Fractal::Fbm;
    fbm.octaves = 6;
    // Top octave at 2^44 * 2^5 = 2^49 lattice units.
    out.push_back({kn + "Fbm6At2p44", fbm, {17592186044416.0, -17592186044416.0, 17592186044416.0}});
  }
  return out;
}

class NoisePropsLarge : public ::testing::TestWithParam<LargeCase> {};

TEST_P(NoisePropsLarge, SameStatisticsAsNearTheOrigin) {
  const LargeCase& c = GetParam();
  const NoiseField f(c.params);
  const double lag = 0.25;
  const int64_t n = 500'000;
  const LagStats near = sample(f, {0.0, 0.0, 0.0}, n, lag, 1);
  const LagStats far = sample(f, c.far, n, lag, 2);
  const double expected = f.expected_sd();
  std::printf("%-22s near: mean %+.5f sd %.5f corr(0.25) %.4f %.4f %.4f | far: mean %+.5f sd %.5f "
              "corr %.4f %.4f %.4f | expected sd %.5f\n",
              c.name.c_str(), near.m.mean(), near.m.sd(), near.lag_corr[0], near.lag_corr[1],
              near.lag_corr[2], far.m.mean(), far.m.sd(), far.lag_corr[0], far.lag_corr[1],
              far.lag_corr[2], expected);
  RecordProperty("far_sd", std::to_string(far.m.sd()));
  EXPECT_EQ(far.m.non_finite, 0);
  EXPECT_LE(std::fabs(far.m.mean()), 0.003);
  EXPECT_LE(std::fabs(near.m.mean()), 0.003);
  EXPECT_NEAR(far.m.sd() / expected, 1.0, 0.02);
  EXPECT_NEAR(near.m.sd() / expected, 1.0, 0.02);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(far.lag_corr[a], near.lag_corr[a], 0.02) << "axis " << a;
    // Not trivially equal to 1 (a field that lost its fraction would be constant per cell and
    // correlate ~0.75 at this lag) nor uncorrelated.
    EXPECT_GT(near.lag_corr[a], 0.3);
    EXPECT_LT(near.lag_corr[a], 0.99);
  }
}

INSTANTIATE_TEST_SUITE_P(ValueAndGradient, NoisePropsLarge, ::testing::ValuesIn(large_cases()),
                         [](const ::testing::TestParamInfo<LargeCase>& param_info) { return param_info.param.name; });

// The fraction survives at 2^30: samples 1e-3 apart differ, and the noise there is not a copy
// of the noise near the origin.
TEST(NoisePropsLargeDetail, FractionResolvedAt2p30) {
  NoiseParams p;
  p.kind = Kind::Gradient;
  const NoiseField f(p);
  const double base = 1073741824.0;
  int equal_neighbours = 0, equal_to_origin = 0;
  Rng rng(5);
  for (int i = 0; i < 10000; ++i) {
    const double x = rng.uniform(0, 1000), y = rng.uniform(0, 1000), z = rng.uniform(0, 1000);
    const float a = f.eval(base + x, base + y, base + z);
    equal_neighbours += a == f.eval(base + x + 1e-3, base + y, base + z);
    equal_to_origin += a == f.eval(x, y, z);
  }
  EXPECT_LT(equal_neighbours, 100);
  EXPECT_LT(equal_to_origin, 100);
}

}  // namespace
}  // namespace nimbus::noise
